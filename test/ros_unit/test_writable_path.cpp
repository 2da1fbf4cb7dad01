// whyNotWritable: the start-time check of ~output_file and ~dataset_bag (issue 12, item 5).

#include "thermal_lidar_calibration/app/files/writable_path.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace tlc = thermal_lidar_calibration;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(WhyNotWritable, AcceptsANewFileInAWritableDirectory) {
  const std::string dir = tlc::test_support::tempDir("tlc_writable_");
  EXPECT_EQ(tlc::whyNotWritable(dir + "/result.yaml"), "");
}

TEST(WhyNotWritable, KeepsAnExistingFileAsItWas) {
  const std::string dir = tlc::test_support::tempDir("tlc_writable_");
  const std::string path = dir + "/result.yaml";
  std::ofstream(path) << "old result\n";
  EXPECT_EQ(tlc::whyNotWritable(path), "");
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "old result");  // opened without truncating
}

TEST(WhyNotWritable, NamesAMissingDirectory) {
  const std::string dir = tlc::test_support::tempDir("tlc_writable_");
  const std::string why = tlc::whyNotWritable(dir + "/missing/result.yaml");
  EXPECT_TRUE(contains(why, dir + "/missing")) << why;
  EXPECT_TRUE(contains(why, "does not exist")) << why;
  EXPECT_TRUE(contains(why, "create it")) << why;
}

TEST(WhyNotWritable, NamesAParentThatIsAFile) {
  const std::string dir = tlc::test_support::tempDir("tlc_writable_");
  std::ofstream(dir + "/plain") << "x";
  const std::string why = tlc::whyNotWritable(dir + "/plain/result.yaml");
  EXPECT_TRUE(contains(why, dir + "/plain")) << why;
  EXPECT_TRUE(contains(why, "not a directory")) << why;
}

TEST(WhyNotWritable, RefusesADirectoryAsTheFile) {
  const std::string dir = tlc::test_support::tempDir("tlc_writable_");
  EXPECT_TRUE(contains(tlc::whyNotWritable(dir), "is a directory"));
  EXPECT_TRUE(contains(tlc::whyNotWritable(dir + "/"), "names a directory"));
}

// /proc takes no new files, not even from root: the probe catches what access(2) would not.
TEST(WhyNotWritable, RefusesADirectoryThatTakesNoNewFiles) {
  const std::string why = tlc::whyNotWritable("/proc/tlc_result.yaml");
  EXPECT_TRUE(contains(why, "cannot create files in /proc")) << why;
}

TEST(WhyNotWritable, RefusesAnEmptyPath) { EXPECT_NE(tlc::whyNotWritable(""), ""); }
