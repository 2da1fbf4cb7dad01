// paced_bag_player: plays a bag to calibration_node as fast as the node takes it, never faster.
//
// `rosbag play -r R` sends at R times the bag's rate whatever the machine: on a busy one the node
// fell behind, its subscriber queues dropped frames, and which pairs it kept (and how many fits
// it made) depended on the machine (issue 22). This player keeps at most --window messages per
// input topic in flight: it sends the next one only once the node's ~status counts
// (images_received, masks_received, clusters_received) show the earlier ones arrived. The node
// sees every message in bag order, and a test's outcome depends on the data alone.
//
// Usage: paced_bag_player BAG [options]
//   --clock                  publish /clock from the bag's times (for /use_sim_time)
//   --status TOPIC           the node's ~status (default /calibration_node/status)
//   --window N               messages per input topic sent and not yet counted (default 10; at
//                            most the node's sync_queue_size, the detectors' input queues)
//   --detectors              the node's masks and clusters come from the detector nodes: each
//                            /thermal/image_raw gives one mask, each /lidar/points one clusters
//   --hold-while-optimizing  send nothing while the node optimizes (a ~stop_when quality fit
//                            then sees the pairs it would see on an infinitely fast machine)
//   --hold-while-drift-busy  send nothing while the drift watch has pairs to test or a new
//                            extrinsic ready for ~auto_update (use with ~auto_update only)
//   --pause-after-pairs N    once the node has kept N pairs and taken everything sent, publish
//                            ~paused and wait for ~resume
//   --start-paused           publish ~paused before the first frame and wait for ~resume
//   --stall-timeout S        give up (exit 1, saying on what) when the node shows no progress
//                            for S seconds (default 300: a guard against hangs, not a clock)
// Topics: ~paused (std_msgs/UInt32, latched: pairs kept at the pause); ~resume
// (std_msgs/UInt32MultiArray: the [images, masks, clusters] other publishers sent the node
// during the pause, or empty); ~done (std_msgs/UInt32, latched: messages played, all of them
// taken by the node). After ~done the player stays up, with its latched topics, until shut down.
//
// Before the first frame it waits until the node is connected to every publisher of the
// topics it subscribes to (the player's, the detectors', a test's /tf_static), and, when the
// node has no intrinsics yet, sends the bag's first camera_info alone until it has.

#include <thermal_lidar_calibration/CalibrationStatus.h>

#include <ros/callback_queue.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/player.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/UInt32.h>
#include <std_msgs/UInt32MultiArray.h>
#include <xmlrpcpp/XmlRpc.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <tuple>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using thermal_lidar_calibration::CalibrationStatus;

struct Options {
  std::string bag;
  bool clock = false;
  std::string status_topic = "/calibration_node/status";
  std::uint32_t window = 10;
  bool detectors = false;
  bool hold_while_optimizing = false;
  bool hold_while_drift_busy = false;
  long pause_after_pairs = -1;
  bool start_paused = false;
  double stall_timeout_s = 300.0;
};

Options parseOptions(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
      return args[++i];
    };
    if (a == "--clock") o.clock = true;
    else if (a == "--status") o.status_topic = value();
    else if (a == "--window") o.window = static_cast<std::uint32_t>(std::stoul(value()));
    else if (a == "--detectors") o.detectors = true;
    else if (a == "--hold-while-optimizing") o.hold_while_optimizing = true;
    else if (a == "--hold-while-drift-busy") o.hold_while_drift_busy = true;
    else if (a == "--pause-after-pairs") o.pause_after_pairs = std::stol(value());
    else if (a == "--start-paused") o.start_paused = true;
    else if (a == "--stall-timeout") o.stall_timeout_s = std::stod(value());
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else if (o.bag.empty()) o.bag = a;
    else throw std::invalid_argument("one bag only (" + o.bag + ", " + a + ")");
  }
  if (o.bag.empty()) throw std::invalid_argument("no bag given");
  if (o.window < 1) throw std::invalid_argument("--window must be at least 1");
  return o;
}

// The node's three input counters of ~status, in this order.
enum Input { kImage = 0, kMask = 1, kClusters = 2 };
using Counts = std::array<std::uint64_t, 3>;

Counts received(const CalibrationStatus& s) {
  return {s.images_received, s.masks_received, s.clusters_received};
}

// The ROS master's view of the graph: topic -> node names.
struct Graph {
  std::map<std::string, std::set<std::string>> publishers, subscribers;
};

Graph systemState() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, true)) {
    throw std::runtime_error("getSystemState failed");
  }
  Graph g;
  for (int kind = 0; kind < 2; ++kind) {
    auto& map = kind == 0 ? g.publishers : g.subscribers;
    for (int i = 0; i < payload[kind].size(); ++i) {
      for (int j = 0; j < payload[kind][i][1].size(); ++j) {
        map[payload[kind][i][0]].insert(static_cast<std::string>(payload[kind][i][1][j]));
      }
    }
  }
  return g;
}

// Whether `node` has an established outbound connection on `topic` to `subscriber` (its slave
// API's getBusInfo: [id, destination, "o"|"i", transport, topic, connected, ...] per link).
bool publishesTo(const std::string& node, const std::string& topic, const std::string& subscriber) {
  XmlRpc::XmlRpcValue args, result, uri;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, uri, false)) return false;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(uri, host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  if (!client.execute("getBusInfo", request, response) || response.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      response.size() < 3) {
    return false;
  }
  XmlRpc::XmlRpcValue& links = response[2];
  for (int i = 0; i < links.size(); ++i) {
    if (links[i].size() < 5) continue;
    if (static_cast<std::string>(links[i][2]) == "o" && static_cast<std::string>(links[i][4]) == topic &&
        static_cast<std::string>(links[i][1]) == subscriber) {
      return true;
    }
  }
  return false;
}

class PacedPlayer {
 public:
  explicit PacedPlayer(Options options) : o_(std::move(options)), nh_(), pnh_("~") {
    status_sub_ = nh_.subscribe(o_.status_topic, 100, &PacedPlayer::onStatus, this);
    resume_sub_ = pnh_.subscribe("resume", 10, &PacedPlayer::onResume, this);
    paused_pub_ = pnh_.advertise<std_msgs::UInt32>("paused", 1, true);
    done_pub_ = pnh_.advertise<std_msgs::UInt32>("done", 1, true);
    if (o_.clock) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  }

  // Returns the process exit status.
  int run() {
    rosbag::Bag bag(o_.bag, rosbag::bagmode::Read);
    rosbag::View view(bag);
    for (const rosbag::ConnectionInfo* c : view.getConnections()) {
      if (publishers_.count(c->topic) == 0) {
        ros::AdvertiseOptions options = rosbag::createAdvertiseOptions(c, 1000);
        publishers_[c->topic] = nh_.advertise(options);
      }
    }
    if (!waitUntil("the node's first ~status on " + o_.status_topic, [&] { return statuses_ > 0; })) return 1;
    taken_offset_ = received(last_);  // whatever reached the node before the player
    // Paused before the connections are checked: what a test publishes before it resumes (a
    // robot's /tf_static) is connected to the node before the first frame too.
    if (o_.start_paused && !pause()) return 1;
    if (!waitUntil("the node and its detectors connected to every publisher", [&] { return connected(); })) {
      return 1;
    }
    if (!last_.intrinsics_known && !primeIntrinsics(view)) return 1;

    std::uint32_t played = 0;
    for (const rosbag::MessageInstance& m : view) {
      const std::vector<Input> inputs = inputsOf(m.getTopic());
      if (!waitUntil("room in the window on " + m.getTopic(), [&] { return mayPublish(inputs); })) return 1;
      publish(m);
      for (Input i : inputs) ++sent_[i];
      ++played;
      if (o_.pause_after_pairs >= 0 && !paused_once_ && last_.pairs_kept >= o_.pause_after_pairs) {
        paused_once_ = true;
        if (!pause()) return 1;
      }
    }
    if (!waitUntil("the node taking the last messages", [&] { return allTaken() && !holding(); })) return 1;
    std_msgs::UInt32 done;
    done.data = played;
    done_pub_.publish(done);
    std::printf("paced_bag_player: %u messages of %s played, all taken by the node\n", played, o_.bag.c_str());
    std::fflush(stdout);
    ros::spin();
    return 0;
  }

 private:
  void onStatus(const CalibrationStatus::ConstPtr& msg) {
    const auto progress = std::make_tuple(msg->images_received, msg->masks_received, msg->clusters_received,
                                          msg->state, msg->pairs_kept, msg->evaluations,
                                          msg->drift_pairs_seen, msg->drift_tests, msg->drift_updates);
    if (statuses_ == 0 || progress != last_progress_) {
      last_progress_ = progress;
      last_progress_time_ = ros::WallTime::now();
    }
    last_ = *msg;
    ++statuses_;
  }

  void onResume(const std_msgs::UInt32MultiArray::ConstPtr& msg) {
    for (std::size_t i = 0; i < msg->data.size() && i < 3; ++i) taken_offset_[i] += msg->data[i];
    ++resumes_;  // counted: a ~resume that comes before the pause is not lost
  }

  // The node's inputs a message of `topic` becomes.
  std::vector<Input> inputsOf(const std::string& topic) const {
    if (topic == "/thermal/image_raw") {
      return o_.detectors ? std::vector<Input>{kImage, kMask} : std::vector<Input>{kImage};
    }
    if (!o_.detectors && topic == "/thermal/human_mask") return {kMask};
    if (!o_.detectors && topic == "/lidar/human_clusters") return {kClusters};
    if (o_.detectors && topic == "/lidar/points") return {kClusters};
    return {};
  }

  std::uint64_t inFlight(Input i) const {
    const std::uint64_t expected = sent_[i] + taken_offset_[i];
    const std::uint64_t taken = received(last_)[i];
    return expected > taken ? expected - taken : 0;
  }

  bool allTaken() const { return inFlight(kImage) + inFlight(kMask) + inFlight(kClusters) == 0; }

  bool holding() const {
    if (o_.hold_while_optimizing && last_.state == CalibrationStatus::OPTIMIZING) return true;
    if (o_.hold_while_drift_busy && (last_.drift_pairs_waiting > 0 || last_.drift_update_ready)) return true;
    return false;
  }

  bool mayPublish(const std::vector<Input>& inputs) const {
    if (holding()) return false;
    for (Input i : inputs) {
      if (inFlight(i) >= o_.window) return false;
    }
    return true;
  }

  void publish(const rosbag::MessageInstance& m) {
    if (o_.clock && m.getTime() > clock_) {
      clock_ = m.getTime();
      rosgraph_msgs::Clock c;
      c.clock = clock_;
      clock_pub_.publish(c);
    }
    publishers_.at(m.getTopic()).publish(m);
  }

  // Everyone the node listens to has it connected, and everyone listening to the player is
  // connected to it. The master knows who registered; the links are made after. Asked at most
  // every 0.1 s (each check is a few XML-RPC calls).
  bool connected() {
    if ((ros::WallTime::now() - last_graph_check_).toSec() < 0.1) return false;
    last_graph_check_ = ros::WallTime::now();
    const Graph g = systemState();
    const auto node_it = g.publishers.find(o_.status_topic);
    if (node_it == g.publishers.end() || node_it->second.empty()) return false;
    const std::string node = *node_it->second.begin();
    std::map<std::string, ros::Publisher> mine = publishers_;
    if (o_.clock) mine["/clock"] = clock_pub_;
    for (const auto& [topic, pub] : mine) {
      const auto subs = g.subscribers.find(topic);
      if (subs != g.subscribers.end() && pub.getNumSubscribers() < subs->second.size()) return false;
    }
    for (const auto& [topic, subscribers] : g.subscribers) {
      if (subscribers.count(node) == 0) continue;
      const auto pubs = g.publishers.find(topic);
      if (pubs == g.publishers.end()) continue;
      for (const std::string& publisher : pubs->second) {
        if (publisher != ros::this_node::getName() && !publishesTo(publisher, topic, node)) return false;
      }
    }
    return true;
  }

  // The bag's first camera_info, alone, until the node has its intrinsics: frames sent before
  // would be dropped by a node that cannot decode them yet.
  bool primeIntrinsics(rosbag::View& view) {
    for (const rosbag::MessageInstance& m : view) {
      if (m.getTopic() != "/thermal/camera_info") continue;
      ros::WallTime sent;
      return waitUntil("the node's intrinsics from " + m.getTopic(), [&] {
        if (last_.intrinsics_known) return true;
        if ((ros::WallTime::now() - sent).toSec() > 1.0) {  // the node unsubscribes once it has one
          publish(m);
          sent = ros::WallTime::now();
        }
        return false;
      });
    }
    return true;  // no camera_info in the bag: the node has ~camera_info_file or waits for one
  }

  bool pause() {
    if (!waitUntil("the node taking everything before the pause", [&] { return allTaken() && !holding(); })) {
      return false;
    }
    const std::uint64_t status_before = statuses_;
    // A ~status published after the last message was taken: its pairs count is final.
    if (!waitUntil("a ~status after the pause", [&] { return statuses_ > status_before; })) return false;
    std_msgs::UInt32 paused;
    paused.data = last_.pairs_kept;
    ++pauses_;
    paused_pub_.publish(paused);
    std::printf("paced_bag_player: paused at %u kept pairs; waiting for %s\n", paused.data,
                pnh_.resolveName("resume").c_str());
    std::fflush(stdout);
    while (ros::ok() && resumes_ < pauses_) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
    return ros::ok();
  }

  // Serves callbacks until `ready`; false (and why, on stderr) if the node shows no progress for
  // --stall-timeout seconds or ROS shuts down.
  bool waitUntil(const std::string& what, const std::function<bool()>& ready) {
    for (;;) {
      if (ready()) return true;
      if (!ros::ok()) return false;
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.002));
      const ros::WallTime since = statuses_ > 0 ? last_progress_time_ : start_;
      if ((ros::WallTime::now() - since).toSec() > o_.stall_timeout_s) {
        std::fprintf(stderr,
                     "paced_bag_player: no progress for %.0f s waiting for %s (sent %llu/%llu/%llu, "
                     "taken %u/%u/%u images/masks/clusters, node %s)\n",
                     o_.stall_timeout_s, what.c_str(), static_cast<unsigned long long>(sent_[0]),
                     static_cast<unsigned long long>(sent_[1]), static_cast<unsigned long long>(sent_[2]),
                     last_.images_received, last_.masks_received, last_.clusters_received,
                     last_.state_name.c_str());
        return false;
      }
    }
  }

  Options o_;
  ros::NodeHandle nh_, pnh_;
  ros::Subscriber status_sub_, resume_sub_;
  ros::Publisher paused_pub_, done_pub_, clock_pub_;
  std::map<std::string, ros::Publisher> publishers_;
  CalibrationStatus last_;
  std::uint64_t statuses_ = 0;
  std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint8_t, std::uint32_t, std::uint64_t,
             std::uint32_t, std::uint32_t, std::uint32_t>
      last_progress_;
  const ros::WallTime start_ = ros::WallTime::now();
  ros::WallTime last_progress_time_ = start_;
  Counts sent_{0, 0, 0};
  Counts taken_offset_{0, 0, 0};
  ros::Time clock_;
  ros::WallTime last_graph_check_;
  bool paused_once_ = false;
  int pauses_ = 0, resumes_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "paced_bag_player");
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  try {
    PacedPlayer player(parseOptions(std::vector<std::string>(args.begin() + 1, args.end())));
    return player.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "paced_bag_player: %s\n", e.what());
    return 1;
  }
}
