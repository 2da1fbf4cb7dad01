// BagAppender: constant-cost, crash-safe appends to a ROS 1 bag (records as in
// http://wiki.ros.org/Bags/Format/2.0; field names and op codes from rosbag/constants.h, record
// headers encoded and parsed by ros::Header, chunks compressed by roslz4 as rosbag does).

#include "thermal_lidar_calibration/ros/bag_appender.hpp"

#include <ros/header.h>
#include <rosbag/constants.h>
#include <roslz4/lz4s.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

const std::string kVersionLine = "#ROSBAG V2.0\n";
constexpr char kJournalMagic[4] = {'T', 'L', 'C', 'J'};
constexpr std::size_t kJournalHead = 28;  // magic, file size, index_pos, prefix length
constexpr int kLz4BlockSizeId = 6;        // rosbag's choice (1 MB blocks)

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("dataset bag " + path + ": " + what);
}

bool fileExists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot read: ") + std::strerror(errno));
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Little-endian fields, as the bag format (and rosbag on every platform it runs on) has them.
template <class T>
std::string bytesOf(T value) {
  std::string s(sizeof(T), '\0');
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    s[i] = static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff);
  }
  return s;
}
template <class T>
T valueOf(const std::string& s, std::size_t at = 0) {
  std::uint64_t v = 0;
  for (std::size_t i = sizeof(T); i-- > 0;) v = (v << 8) | static_cast<unsigned char>(s.at(at + i));
  return static_cast<T>(v);
}
std::string timeBytes(const ros::Time& t) { return bytesOf(t.sec) + bytesOf(t.nsec); }
std::string opBytes(unsigned char op) { return std::string(1, static_cast<char>(op)); }

void appendRecord(std::string& out, const ros::M_string& fields, const std::string& data) {
  boost::shared_array<std::uint8_t> header;
  std::uint32_t header_len = 0;
  ros::Header::write(fields, header, header_len);
  out += bytesOf(header_len);
  out.append(reinterpret_cast<const char*>(header.get()), header_len);
  out += bytesOf(static_cast<std::uint32_t>(data.size()));
  out += data;
}

// One record read from `bytes` at `pos`: its header fields, and where it ends.
struct Record {
  ros::M_string fields;
  std::size_t end = 0;
};
Record readRecord(const std::string& path, const std::string& bytes, std::size_t pos) {
  if (pos + 4 > bytes.size()) fail(path, "the index is truncated");
  const auto header_len = valueOf<std::uint32_t>(bytes, pos);
  if (header_len > bytes.size() - pos - 4 || bytes.size() - pos - 4 - header_len < 4) {
    fail(path, "the index is truncated");
  }
  ros::Header header;
  std::string error;
  std::string header_bytes = bytes.substr(pos + 4, header_len);
  if (!header.parse(reinterpret_cast<std::uint8_t*>(&header_bytes[0]), header_len, error)) {
    fail(path, "bad record header in the index: " + error);
  }
  const std::size_t data_at = pos + 4 + header_len + 4;
  const auto data_len = valueOf<std::uint32_t>(bytes, data_at - 4);
  if (data_len > bytes.size() - data_at) fail(path, "the index is truncated");
  return {*header.getValues(), data_at + data_len};
}

const std::string& field(const std::string& path, const ros::M_string& fields,
                         const std::string& name, std::size_t size) {
  const auto it = fields.find(name);
  if (it == fields.end() || (size != 0 && it->second.size() != size)) {
    fail(path, "record without a valid '" + name + "' field");
  }
  return it->second;
}

// Writes all of `bytes` at `offset`; false (errno set) on any failure or short write.
bool writeAt(int fd, const std::string& bytes, std::uint64_t offset) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::pwrite(fd, bytes.data() + done, bytes.size() - done,
                               static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// One pair's messages as one chunk: a connection record for each topic new to the bag, then the
// message data records; per connection, the (time, offset in the chunk) of its messages for the
// index data records.
struct NewChunk {
  std::string chunk;
  std::string new_connections;               // the connection records of the new topics
  std::map<std::string, std::uint32_t> ids;  // topic -> connection id, old and new
  std::uint32_t next_id = 0;
  std::map<std::uint32_t, std::pair<std::uint32_t, std::string>> entries;  // id -> count, entries
  ros::Time start, end;
};

NewChunk buildChunk(const std::vector<BagAppender::Message>& group, std::map<std::string, std::uint32_t> ids,
                    std::uint32_t next_id) {
  NewChunk c;
  c.start = c.end = group.front().time;
  for (const BagAppender::Message& m : group) {
    auto it = ids.find(m.topic);
    if (it == ids.end()) {
      it = ids.emplace(m.topic, next_id++).first;
      const ros::M_string connection = {{"topic", m.topic},
                                        {"type", m.datatype},
                                        {"md5sum", m.md5sum},
                                        {"message_definition", m.definition}};
      boost::shared_array<std::uint8_t> data;
      std::uint32_t data_len = 0;
      ros::Header::write(connection, data, data_len);
      std::string record;
      appendRecord(record,
                   {{rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_CONNECTION)},
                    {rosbag::TOPIC_FIELD_NAME, m.topic},
                    {rosbag::CONNECTION_FIELD_NAME, bytesOf(it->second)}},
                   std::string(reinterpret_cast<const char*>(data.get()), data_len));
      c.chunk += record;  // rosbag reindex finds connections in the chunks
      c.new_connections += record;
    }
    auto& [count, index] = c.entries[it->second];
    ++count;
    index += timeBytes(m.time) + bytesOf(static_cast<std::uint32_t>(c.chunk.size()));
    appendRecord(c.chunk,
                 {{rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_MSG_DATA)},
                  {rosbag::CONNECTION_FIELD_NAME, bytesOf(it->second)},
                  {rosbag::TIME_FIELD_NAME, timeBytes(m.time)}},
                 std::string(reinterpret_cast<const char*>(m.bytes.data()), m.bytes.size()));
    c.start = std::min(c.start, m.time);
    c.end = std::max(c.end, m.time);
  }
  c.ids = std::move(ids);
  c.next_id = next_id;
  return c;
}

// LZ4 as rosbag does. False when LZ4 cannot shrink the chunk: it is stored as it is. (roslz4
// takes the input as char* but does not write it.)
bool compressLz4(std::string& chunk, std::string* compressed) {
  compressed->assign(chunk.size() + chunk.size() / 100 + 1024, '\0');
  auto compressed_len = static_cast<unsigned int>(compressed->size());
  const bool lz4 = roslz4_buffToBuffCompress(&chunk[0], static_cast<unsigned int>(chunk.size()),
                                             &(*compressed)[0], &compressed_len,
                                             kLz4BlockSizeId) == ROSLZ4_OK &&
                   compressed_len < chunk.size();
  compressed->resize(compressed_len);
  return lz4;
}

}  // namespace

BagAppender::BagAppender(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw std::invalid_argument("dataset bag path is empty");
  exists_ = fileExists(path_);
  if (exists_) readIndex();
}

// The file header, then from index_pos to the end: connection records, then chunk-info records.
// Kept verbatim; only the topics' connection ids are needed to append.
void BagAppender::readIndex() {
  recoverBagAppend(path_);
  const std::string bytes = readAll(path_);
  if (bytes.compare(0, kVersionLine.size(), kVersionLine) != 0) fail(path_, "not a ROS 1 (v2.0) bag");
  const Record header = readRecord(path_, bytes, kVersionLine.size());
  if (field(path_, header.fields, rosbag::OP_FIELD_NAME, 1) != opBytes(rosbag::OP_FILE_HEADER)) {
    fail(path_, "no file header record");
  }
  if (header.fields.count(rosbag::ENCRYPTOR_FIELD_NAME) != 0) {
    fail(path_, "the bag is encrypted; give ~dataset_bag a new file");
  }
  index_pos_ = valueOf<std::uint64_t>(field(path_, header.fields, rosbag::INDEX_POS_FIELD_NAME, 8));
  connection_count_ =
      valueOf<std::uint32_t>(field(path_, header.fields, rosbag::CONNECTION_COUNT_FIELD_NAME, 4));
  chunk_count_ = valueOf<std::uint32_t>(field(path_, header.fields, rosbag::CHUNK_COUNT_FIELD_NAME, 4));
  file_size_ = bytes.size();
  if (index_pos_ < header.end || index_pos_ > file_size_) {
    fail(path_, "the bag is not indexed (interrupted without a journal); run 'rosbag reindex " +
                    path_ + "' and try again");
  }
  std::size_t pos = static_cast<std::size_t>(index_pos_);
  for (std::uint32_t i = 0; i < connection_count_; ++i) {
    const Record r = readRecord(path_, bytes, pos);
    const auto id = valueOf<std::uint32_t>(field(path_, r.fields, rosbag::CONNECTION_FIELD_NAME, 4));
    // A bag from rosbag's append mode has several connections per topic: any one serves.
    connection_ids_[field(path_, r.fields, rosbag::TOPIC_FIELD_NAME, 0)] = id;
    next_connection_id_ = std::max(next_connection_id_, id + 1);
    pos = r.end;
  }
  connection_records_ = bytes.substr(index_pos_, pos - index_pos_);
  const std::size_t chunk_infos_at = pos;
  for (std::uint32_t i = 0; i < chunk_count_; ++i) pos = readRecord(path_, bytes, pos).end;
  chunk_infos_ = bytes.substr(chunk_infos_at, pos - chunk_infos_at);
  if (pos != bytes.size()) fail(path_, "unexpected bytes after the index");
}

std::string BagAppender::fileHeader(std::uint64_t index_pos, std::uint32_t chunks) const {
  const ros::M_string fields = {
      {rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_FILE_HEADER)},
      {rosbag::INDEX_POS_FIELD_NAME, bytesOf(index_pos)},
      {rosbag::CONNECTION_COUNT_FIELD_NAME, bytesOf(connection_count_)},
      {rosbag::CHUNK_COUNT_FIELD_NAME, bytesOf(chunks)}};
  std::string record;
  appendRecord(record, fields, "");
  // Padded like rosbag's, so that the header can be rewritten in place.
  const std::size_t header_len = record.size() - 8;
  record.resize(record.size() - 4);
  const std::uint32_t padding =
      header_len < rosbag::FILE_HEADER_LENGTH ? rosbag::FILE_HEADER_LENGTH - header_len : 0;
  record += bytesOf(padding) + std::string(padding, ' ');
  return kVersionLine + record;
}

void BagAppender::append(const std::vector<Message>& group) {
  if (group.empty()) return;
  NewChunk c = buildChunk(group, connection_ids_, next_connection_id_);
  if (c.chunk.size() > std::numeric_limits<std::uint32_t>::max() / 2) {
    fail(path_, "a pair of " + std::to_string(c.chunk.size()) + " bytes is too large for one chunk");
  }
  std::string compressed;
  const bool lz4 = compressLz4(c.chunk, &compressed);
  const std::string& chunk = c.chunk;
  const auto& entries = c.entries;

  // What goes where the old index was: the chunk, its index data records, then the new index.
  const std::uint64_t chunk_pos = exists_ ? index_pos_ : fileHeader(0, 0).size();
  std::string tail;
  appendRecord(tail,
               {{rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_CHUNK)},
                {rosbag::COMPRESSION_FIELD_NAME, lz4 ? "lz4" : "none"},
                {rosbag::SIZE_FIELD_NAME, bytesOf(static_cast<std::uint32_t>(chunk.size()))}},
               lz4 ? compressed : chunk);
  std::string connection_counts;
  for (const auto& [id, count_index] : entries) {
    appendRecord(tail,
                 {{rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_INDEX_DATA)},
                  {rosbag::VER_FIELD_NAME, bytesOf(rosbag::INDEX_VERSION)},
                  {rosbag::CONNECTION_FIELD_NAME, bytesOf(id)},
                  {rosbag::COUNT_FIELD_NAME, bytesOf(count_index.first)}},
                 count_index.second);
    connection_counts += bytesOf(id) + bytesOf(count_index.first);
  }
  std::string chunk_info;
  appendRecord(chunk_info,
               {{rosbag::OP_FIELD_NAME, opBytes(rosbag::OP_CHUNK_INFO)},
                {rosbag::VER_FIELD_NAME, bytesOf(rosbag::CHUNK_INFO_VERSION)},
                {rosbag::CHUNK_POS_FIELD_NAME, bytesOf(chunk_pos)},
                {rosbag::START_TIME_FIELD_NAME, timeBytes(c.start)},
                {rosbag::END_TIME_FIELD_NAME, timeBytes(c.end)},
                {rosbag::COUNT_FIELD_NAME, bytesOf(static_cast<std::uint32_t>(entries.size()))}},
               connection_counts);
  const std::uint64_t new_index_pos = chunk_pos + tail.size();
  tail += connection_records_ + c.new_connections + chunk_infos_ + chunk_info;

  const std::string old_header = fileHeader(index_pos_, chunk_count_);
  const std::uint32_t connections_before = connection_count_;
  connection_count_ += c.next_id - next_connection_id_;
  const std::string header = fileHeader(new_index_pos, chunk_count_ + 1);
  try {
    if (exists_) {
      writeInPlace(old_header, header, tail);
    } else {
      writeNew(header, tail);
    }
  } catch (...) {
    connection_count_ = connections_before;
    throw;
  }
  exists_ = true;
  connection_ids_ = c.ids;
  next_connection_id_ = c.next_id;
  connection_records_ += c.new_connections;
  chunk_infos_ += chunk_info;
  ++chunk_count_;
  index_pos_ = new_index_pos;
  file_size_ = chunk_pos + tail.size();
}

void BagAppender::writeNew(const std::string& header, const std::string& tail) {
  const std::string tmp = path_ + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  bool ok = fd >= 0 && writeAt(fd, header, 0) && writeAt(fd, tail, header.size());
  const int error = errno;
  ok = (fd < 0 || ::close(fd) == 0) && ok;
  if (!ok || std::rename(tmp.c_str(), path_.c_str()) != 0) {
    const int reason = ok ? errno : error;
    std::remove(tmp.c_str());
    fail(path_, "cannot write " + tmp + ": " + std::strerror(reason));
  }
}

// The journal holds what this append overwrites: the file header and the old index (kept in
// memory, so nothing is read back). Its layout: magic, old file size, old index_pos, header
// length, header, index.
void BagAppender::writeInPlace(const std::string& old_header, const std::string& header,
                               const std::string& tail) {
  const std::string old_index = connection_records_ + chunk_infos_;
  std::string journal(kJournalMagic, 4);
  journal += bytesOf(file_size_) + bytesOf(index_pos_) +
             bytesOf(static_cast<std::uint64_t>(old_header.size())) + old_header + old_index;
  const std::string journal_path = path_ + ".journal";
  const std::string journal_tmp = journal_path + ".tmp";
  {
    const int fd = ::open(journal_tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    bool ok = fd >= 0 && writeAt(fd, journal, 0);
    const int error = errno;
    ok = (fd < 0 || ::close(fd) == 0) && ok;
    if (!ok) {
      std::remove(journal_tmp.c_str());
      fail(path_, "cannot write the journal " + journal_tmp + ": " + std::strerror(error));
    }
  }
  if (std::rename(journal_tmp.c_str(), journal_path.c_str()) != 0) {
    fail(path_, "cannot rename the journal: " + std::string(std::strerror(errno)));
  }
  const int fd = ::open(path_.c_str(), O_WRONLY);
  bool ok = fd >= 0 && writeAt(fd, tail, index_pos_) && writeAt(fd, header, 0);
  const int error = errno;
  ok = (fd < 0 || ::close(fd) == 0) && ok;
  if (!ok) {
    // Put the bag back as it was before this append (every earlier pair readable).
    std::string restored = "the bag was restored to its earlier pairs";
    try {
      recoverBagAppend(path_);
    } catch (const std::exception& r) {
      restored = std::string("restoring it failed too (") + r.what() +
                 "); the journal is kept, start with ~resume to restore it";
    }
    fail(path_, std::string("cannot append: ") + std::strerror(error) + "; " + restored);
  }
  std::remove(journal_path.c_str());
}

bool recoverBagAppend(const std::string& path) {
  std::remove((path + ".journal.tmp").c_str());
  std::remove((path + ".tmp").c_str());
  const std::string journal_path = path + ".journal";
  if (!fileExists(journal_path)) return false;
  const std::string journal = readAll(journal_path);
  const auto damaged = [&] {
    fail(path, "journal " + journal_path + " is damaged; delete it and run 'rosbag reindex'");
  };
  if (journal.size() < kJournalHead || journal.compare(0, 4, kJournalMagic, 4) != 0) damaged();
  const auto size = valueOf<std::uint64_t>(journal, 4);
  const auto index_pos = valueOf<std::uint64_t>(journal, 12);
  const auto prefix_len = valueOf<std::uint64_t>(journal, 20);
  if (index_pos > size || prefix_len > journal.size() - kJournalHead ||
      kJournalHead + prefix_len + (size - index_pos) != journal.size()) {
    damaged();
  }
  const int fd = ::open(path.c_str(), O_WRONLY);
  bool ok = fd >= 0 && writeAt(fd, journal.substr(kJournalHead, prefix_len), 0) &&
            writeAt(fd, journal.substr(kJournalHead + prefix_len), index_pos) &&
            ::ftruncate(fd, static_cast<off_t>(size)) == 0;
  const int error = errno;
  ok = (fd < 0 || ::close(fd) == 0) && ok;
  if (!ok) fail(path, "recovery from the journal failed: " + std::string(std::strerror(error)));
  std::remove(journal_path.c_str());
  return true;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
