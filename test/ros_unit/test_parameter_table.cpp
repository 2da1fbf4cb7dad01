// The descriptor machinery on a small table of its own: one row per key gives loading,
// validation, describe and documentation, for every row type.

#include "thermal_lidar_calibration/app/parameters/parameter_docs.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>

namespace tlc = thermal_lidar_calibration;
using namespace tlc;

namespace {

enum class Mode : std::uint8_t { kFast, kSlow };
struct Inner {
  double gain = 0.5;
  Mode mode = Mode::kFast;
};
struct Toy {
  Inner inner;
  int count = 3;
  std::uint64_t seed = 7;
  bool verbose = false;
  std::string name;
  std::string out = "out.yaml";
  int level = 2;
};

ParameterTable<Toy> makeToyTable() {
  ParameterTable<Toy> t;
  auto top = t.fields();
  auto inner = t.group<Inner>([](Toy& p) -> Inner& { return p.inner; });
  t.section("First");
  top.integer("count", &Toy::count, {1, 10}, "people", "how many");
  top.integer("seed", &Toy::seed, {0, std::numeric_limits<long long>::max()}, "", "seed");
  inner.real("gain", &Inner::gain, aboveRange(0, 1e-3 * 1e3), "m", "gain", "a note");
  t.section("Second");
  inner.choice("mode", &Inner::mode, {{"fast", Mode::kFast}, {"slow", Mode::kSlow}},
               "must be 'fast' or 'slow'", "speed");
  top.integerChoice("level", &Toy::level, {{1, 1}, {2, 2}}, "must be 1 or 2", "level");
  top.boolean("verbose", &Toy::verbose, "talk more");
  top.text("name", &Toy::name, TextRule::optional("anonymous"), "who");
  top.text("out", &Toy::out, TextRule::required("must name a file"), "where");
  return t;
}

std::string yamlFile(const std::string& text) {
  const std::string path = test_support::tempDir("tlc_param_table_") + "/p.yaml";
  std::ofstream(path) << text;
  return path;
}

Toy load(const std::string& text) {
  Toy toy;
  makeToyTable().load(*makeYamlParameterSource(yamlFile(text)), toy);
  return toy;
}

std::string errorOf(const std::string& text) {
  return test_support::errorOf([&] { load(text); });
}

}  // namespace

TEST(ParameterTable, AbsentKeysKeepTheMemberInitialisers) {
  const Toy toy = load("");
  EXPECT_EQ(toy.count, 3);
  EXPECT_EQ(toy.seed, 7u);
  EXPECT_DOUBLE_EQ(toy.inner.gain, 0.5);
  EXPECT_EQ(toy.inner.mode, Mode::kFast);
  EXPECT_EQ(toy.out, "out.yaml");
}

TEST(ParameterTable, EveryRowTypeReadsItsField) {
  const Toy toy = load(
      "count: 10\nseed: 12345678901\ngain: 1\nmode: slow\nlevel: 1\nverbose: true\nname: bob\n"
      "out: x.yaml\n");
  EXPECT_EQ(toy.count, 10);
  EXPECT_EQ(toy.seed, 12345678901u);
  EXPECT_DOUBLE_EQ(toy.inner.gain, 1.0);
  EXPECT_EQ(toy.inner.mode, Mode::kSlow);
  EXPECT_EQ(toy.level, 1);
  EXPECT_TRUE(toy.verbose);
  EXPECT_EQ(toy.name, "bob");
  EXPECT_EQ(toy.out, "x.yaml");
}

TEST(ParameterTable, BadValuesNameKeyValueAndAllowedValues) {
  EXPECT_EQ(errorOf("count: 11\n"), "parameter 'count' = 11: must be an integer in [1, 10]");
  EXPECT_EQ(errorOf("seed: -1\n"),
            "parameter 'seed' = -1: must be an integer in [0, 9223372036854775807]");
  EXPECT_EQ(errorOf("gain: 0\n"), "parameter 'gain' = 0: must be a number in (0, 1]");
  EXPECT_EQ(errorOf("gain: .inf\n").rfind("parameter 'gain' = ", 0), 0u);
  EXPECT_EQ(errorOf("mode: medium\n"), "parameter 'mode' = 'medium': must be 'fast' or 'slow'");
  EXPECT_EQ(errorOf("level: 3\n"), "parameter 'level' = 3: must be 1 or 2");
  EXPECT_EQ(errorOf("level: one\n"), "parameter 'level' = 'one': must be 1 or 2");
  EXPECT_EQ(errorOf("verbose: 2\n"), "parameter 'verbose' = 2: must be true or false");
  EXPECT_EQ(errorOf("out: ''\n"), "parameter 'out' = '': must name a file");
  EXPECT_EQ(errorOf("name: [a, b]\n"), "parameter 'name' = <not a scalar>: must be a string");
}

TEST(ParameterTable, DescribeAndDocsComeFromTheSameRows) {
  const auto table = makeToyTable();
  Toy toy;
  toy.inner.gain = 0.25;
  const auto d = table.describe(toy);
  ASSERT_EQ(d.size(), 8u);
  EXPECT_EQ(d[0], (std::pair<std::string, std::string>{"count", "3"}));
  EXPECT_EQ(d[2].second, "0.25");
  EXPECT_EQ(d[3].second, "fast");
  EXPECT_EQ(d[6].second, "'' (anonymous)");
  EXPECT_EQ(table.keys(), (std::vector<std::string>{"count", "seed", "gain", "mode", "level",
                                                    "verbose", "name", "out"}));
  const auto docs = table.docs();
  EXPECT_EQ(docs[0].section, "First");
  EXPECT_EQ(docs[0].meaning, "how many, people; integer [1, 10]");
  EXPECT_EQ(docs[1].meaning, "seed; integer >= 0");
  EXPECT_EQ(docs[2].default_yaml, "0.5");
  EXPECT_EQ(docs[2].meaning, "gain, m; (0, 1]; a note");
  EXPECT_EQ(docs[3].section, "Second");
  EXPECT_EQ(docs[3].meaning, "speed; {fast, slow}");
  EXPECT_EQ(docs[4].meaning, "level; {1, 2}");
  EXPECT_EQ(docs[5].meaning, "talk more; bool");
  EXPECT_EQ(docs[6].default_yaml, "\"\"");
  EXPECT_EQ(docs[6].meaning, "who; \"\" = anonymous");
  EXPECT_EQ(docs[7].meaning, "where; non-empty");
}

TEST(ParameterTable, DuplicateKeysAreAProgrammingError) {
  ParameterTable<Toy> t;
  t.fields().integer("count", &Toy::count, {1, 10}, "", "a");
  EXPECT_THROW(t.fields().integer("count", &Toy::level, {1, 10}, "", "b"), std::logic_error);
}

TEST(ParameterTable, YamlNumbersReadBackAsNumbersInRosparam) {
  // PyYAML (rosparam) needs a '.' and a signed exponent to read a float.
  EXPECT_EQ(parameter_detail::yamlReal(1e-6), "1.0e-06");
  EXPECT_EQ(parameter_detail::yamlReal(5), "5.0");
  EXPECT_EQ(parameter_detail::yamlReal(0.15), "0.15");
  EXPECT_EQ(parameter_detail::yamlText(""), "\"\"");
  EXPECT_EQ(parameter_detail::yamlText("a/b.yaml"), "a/b.yaml");
  EXPECT_EQ(parameter_detail::yamlText("true"), "\"true\"");
  EXPECT_EQ(parameter_detail::yamlText("a: b"), "\"a: b\"");
}

TEST(ParameterDocs, RenderedYamlLoadsBackToTheDefaults) {
  const auto table = makeToyTable();
  const std::string text = renderDefaultYaml(table.docs());
  EXPECT_NE(text.find("\n# --- First ---"), std::string::npos);
  EXPECT_NE(text.find("count: 3                           # how many, people; integer [1, 10]\n"),
            std::string::npos);
  Toy toy;
  toy.count = 9;  // overwritten by the file's default
  table.load(*makeYamlParameterSource(yamlFile(text)), toy);
  EXPECT_EQ(table.describe(toy), table.describe(Toy{}));
}

TEST(ParameterDocs, MarkdownAndMarkers) {
  const std::string md = renderParameterMarkdown(makeToyTable().docs());
  EXPECT_NE(md.find("| **Second** | | |\n"), std::string::npos);
  EXPECT_NE(md.find("| `name` | `\"\"` | who; \"\" = anonymous |\n"), std::string::npos);
  const std::string text = "a\nBEGIN\nold\nEND\nz\n";
  EXPECT_EQ(replaceMarkedBlock(text, "BEGIN", "END", "new\n"), "a\nBEGIN\nnew\nEND\nz\n");
  EXPECT_EQ(markedBlock(text, "BEGIN", "END"), "old\n");
  EXPECT_THROW(markedBlock("a\n", "BEGIN", "END"), std::invalid_argument);
}
