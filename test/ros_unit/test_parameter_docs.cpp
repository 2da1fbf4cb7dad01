// config/default.yaml and the parameter reference (docs/parameters.md) are rendered from the
// parameter tables; this test fails while the committed files disagree with the tables. To
// rewrite them:
//   bash scripts/update_parameter_docs.sh   (runs this test with TLC_UPDATE_PARAMETER_DOCS=1)

#include "thermal_lidar_calibration/app/parameters/parameter_docs.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_catalog.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tlc = thermal_lidar_calibration;

namespace {

// Tests run in test/; the files are next to it.
const char* const kDefaultYaml = "../config/default.yaml";
const char* const kParameterReference = "../docs/parameters.md";

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool updating() {
  const char* v = std::getenv("TLC_UPDATE_PARAMETER_DOCS");
  return v != nullptr && std::string(v) == "1";
}

const char* const kHowToFix =
    "out of date with the parameter tables: run bash scripts/update_parameter_docs.sh";

}  // namespace

TEST(ParameterDocs, DefaultYamlIsRenderedFromTheTables) {
  const std::string expected = tlc::renderDefaultYaml(tlc::allParameterDocs());
  if (updating()) std::ofstream(kDefaultYaml) << expected;
  EXPECT_EQ(readText(kDefaultYaml), expected) << kDefaultYaml << " " << kHowToFix;
}

TEST(ParameterDocs, ReferenceTableIsRenderedFromTheTables) {
  const std::string expected = tlc::renderParameterMarkdown(tlc::allParameterDocs());
  const std::string reference = readText(kParameterReference);
  if (updating()) {
    std::ofstream(kParameterReference) << tlc::replaceMarkedBlock(
        reference, tlc::kParameterTableBegin, tlc::kParameterTableEnd, expected);
  }
  EXPECT_EQ(tlc::markedBlock(readText(kParameterReference), tlc::kParameterTableBegin,
                             tlc::kParameterTableEnd),
            expected)
      << kParameterReference << " " << kHowToFix;
}

TEST(ParameterDocs, EveryKeyOnceAcrossAllTables) {
  std::vector<std::string> keys = tlc::knownParameterKeys();
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end());
}
