// Serialize-described structs (config/param_archive.h): the strict loader, the validation hook,
// the dump of defaults, bit-exact round trips, and summary.json as a --config file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "config/yaml_read_archive.h"
#include "config/yaml_write_archive.h"
#include "tests/support/message_of.h"
#include "tests/support/param_round_trip.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::config {
namespace {

using test_support::MessageOf;
using ::testing::AllOf;
using ::testing::HasSubstr;

enum class Law { kLqr, kProportional };

struct Gains {
  double p_per_s = 4.0;
  Eigen::Vector3i counts{7, 7, 5};
  void Validate() const {
    if (!(p_per_s >= 0.0)) throw std::invalid_argument("Gains.p_per_s must be >= 0");
  }
};

struct Stack {
  double rate_hz = 100.0;
  float scale = 0.5f;
  int rotors = 4;
  bool enabled = true;
  std::string camera = "front";
  std::uint64_t seed = 7;
  Law law = Law::kLqr;
  Eigen::Vector3d p_BC = Eigen::Vector3d(0.1, 0.0, -0.05);
  Eigen::Matrix3d R_BC = Eigen::Matrix3d::Identity();
  Eigen::VectorXd weights = Eigen::Vector2d(1.0, 2.0);
  std::vector<double> times_s{0.5, 1.5};
  double min_height_m = -std::numeric_limits<double>::infinity();
  Gains gains;
  Gains outer;  // written flat under `loop` together with rate_hz (VisitSection)
};

const EnumNames<Law> kLawNames = {{"lqr", Law::kLqr}, {"p", Law::kProportional}};

template <typename Archive>
void Serialize(Archive* a, Gains* p) {
  a->Visit(APERTURE_NVP(p, p_per_s));
  a->Visit(APERTURE_NVP(p, counts));
}

template <typename Archive>
void Serialize(Archive* a, Stack* p) {
  a->Visit(APERTURE_NVP(p, scale));
  a->Visit(APERTURE_NVP(p, rotors));
  a->Visit(APERTURE_NVP(p, enabled));
  a->Visit(APERTURE_NVP(p, camera));
  a->Visit(APERTURE_NVP(p, seed));
  a->Visit(APERTURE_NVP(p, law), kLawNames);
  a->Visit(APERTURE_NVP(p, p_BC));
  a->Visit(APERTURE_NVP(p, R_BC));
  a->Visit(APERTURE_NVP(p, weights));
  a->Visit(APERTURE_NVP(p, times_s));
  a->Visit(APERTURE_NVP(p, min_height_m));
  a->Visit(APERTURE_NVP(p, gains));
  a->VisitSection("loop", [p](auto* loop) {
    loop->Visit(APERTURE_NVP(p, rate_hz));
    loop->Visit("outer_p_per_s", &p->outer.p_per_s);
  });
}

Stack LoadStack(const std::string& yaml) {
  ParamReader reader(YAML::Load(yaml), "stack.yaml");
  Stack stack;
  LoadParams(reader, &stack);
  return stack;
}

TEST(ParamArchive, LoadsPresentKeysAndKeepsDefaults) {
  const Stack stack = LoadStack(R"(
rotors: 6
law: p
camera: down
gains: {counts: [3, 4, 2]}
loop: {rate_hz: 250}
)");
  EXPECT_EQ(stack.rotors, 6);
  EXPECT_EQ(stack.law, Law::kProportional);
  EXPECT_EQ(stack.camera, "down");
  EXPECT_EQ(stack.gains.counts, Eigen::Vector3i(3, 4, 2));
  EXPECT_EQ(stack.gains.p_per_s, Gains().p_per_s);
  EXPECT_EQ(stack.rate_hz, 250.0);
  EXPECT_EQ(stack.outer.p_per_s, Gains().p_per_s);
  EXPECT_EQ(stack.p_BC, Stack().p_BC);
}

TEST(ParamArchive, DumpDocumentsEveryDefault) {
  const std::string yaml = DumpYaml(Stack{});
  EXPECT_THAT(yaml, AllOf(HasSubstr("rotors: 4"), HasSubstr("law: lqr"), HasSubstr("seed: 7"),
                          HasSubstr("p_BC: [0.1, 0, -0.05]"), HasSubstr("min_height_m: -.inf"),
                          HasSubstr("counts: [7, 7, 5]"), HasSubstr("rate_hz: 100"),
                          HasSubstr("outer_p_per_s: 4"), HasSubstr("times_s: [0.5, 1.5]")))
      << yaml;
}

TEST(ParamArchive, DumpLoadDumpIsTheSameForEveryPerturbedField) {
  test_support::ExpectRoundTrip(Stack{}, {"min_height_m"});  // -inf stays -inf
}

// Values whose decimal text needs all 17 digits, subnormals and non-finite values come back with
// the same bits.
TEST(ParamArchive, NumbersRoundTripBitExactly) {
  for (const double value : {0.1, 1.0 / 3.0, 2.0 / 3.0 * 1e-300, 5e-324, -0.0, 1e12, -1e12}) {
    Stack stack;
    stack.rate_hz = value;
    stack.times_s = {value};
    const Stack loaded = LoadStack(DumpYaml(stack));
    EXPECT_EQ(std::memcmp(&loaded.rate_hz, &value, sizeof(double)), 0) << DumpYaml(stack);
    EXPECT_EQ(std::memcmp(&loaded.times_s[0], &value, sizeof(double)), 0);
  }
  // What no parameter may hold is dumped as such (.nan, .inf, 1e+308) and refused on loading,
  // naming the key (issue 18: every number finite and in range).
  for (const double value :
       {1e308, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Stack stack;
    stack.times_s = {value};
    EXPECT_THAT(MessageOf([&] { LoadStack(DumpYaml(stack)); }),
                AllOf(HasSubstr("times_s[0]"), HasSubstr("a finite number")));
  }
}

TEST(ParamArchive, UnknownKeysNameFileLineKeyAndKnownKeys) {
  const std::string nested = MessageOf([] { LoadStack("rotors: 4\ngains: {gian: 1}\n"); });
  EXPECT_THAT(nested, AllOf(HasSubstr("stack.yaml:2:"), HasSubstr("unknown key 'gains.gian'"),
                            HasSubstr("known keys: counts, p_per_s")));
  const std::string top = MessageOf([] { LoadStack("rotor: 4"); });
  EXPECT_THAT(top, AllOf(HasSubstr("stack.yaml:1:1"), HasSubstr("'rotor'"), HasSubstr("rotors")));
  const std::string section = MessageOf([] { LoadStack("loop: {rate: 4}"); });
  EXPECT_THAT(section, AllOf(HasSubstr("loop.rate"), HasSubstr("outer_p_per_s, rate_hz")));
}

TEST(ParamArchive, TypeErrorsNameKeyExpectedTypeAndValue) {
  EXPECT_THAT(MessageOf([] { LoadStack("rotors: 2.5"); }),
              AllOf(HasSubstr("stack.yaml:1:9"), HasSubstr("key 'rotors' expects an integer"),
                    HasSubstr("got '2.5'")));
  EXPECT_THAT(MessageOf([] { LoadStack("gains: {counts: [1, 2]}"); }),
              AllOf(HasSubstr("gains.counts"), HasSubstr("a sequence of 3 numbers")));
  EXPECT_THAT(MessageOf([] { LoadStack("law: pid"); }),
              AllOf(HasSubstr("'law'"), HasSubstr("one of: lqr, p")));
  EXPECT_THAT(MessageOf([] { LoadStack("seed: -1"); }),
              AllOf(HasSubstr("'seed'"), HasSubstr("non-negative integer")));
}

TEST(ParamArchive, ValidationNamesTheKeyAndWhereItCameFrom) {
  // The validator's "Gains.p_per_s" is the key path gains.p_per_s at its line and column.
  EXPECT_EQ(MessageOf([] { LoadStack("gains: {p_per_s: -1}"); }),
            "stack.yaml:1:18: gains.p_per_s must be >= 0");
}

// A string that reads like a number stays a string in ToJson and in a reloaded dump.
TEST(ParamArchive, NumericLookingStringsStayStrings) {
  Stack stack;
  stack.camera = "1.5";
  ConfigTree tree;
  tree.PutParams("stack", stack);
  EXPECT_THAT(tree.ToJson(), HasSubstr("\"camera\":\"1.5\""));
  EXPECT_THAT(tree.ToJson(), HasSubstr("\"rotors\":4"));
  ParamReader root = tree.Reader();
  Stack loaded;
  root.ReadSection("stack", &loaded);
  EXPECT_EQ(loaded.camera, "1.5");
}

class SummaryAsConfigTest : public aperture::testing::TempDirectoryTest {};

// A run's summary.json given to --config contributes its "config" section only: the effective
// configuration the run wrote with PutParams and ToJson loads back to the same struct.
TEST_F(SummaryAsConfigTest, SummaryJsonContributesItsConfigSection) {
  Stack stack;
  stack.rate_hz = 1.0 / 3.0;
  stack.camera = "true";
  stack.law = Law::kProportional;
  ConfigTree written;
  written.PutParams("stack", stack);
  const std::string summary =
      WriteFile("summary.json",
                "{\"command\": \"sim\", \"status\": \"ok\", \"timing\": {\"total_s\": 1},\n"
                " \"config\": " +
                    written.ToJson() + "}\n");
  const ConfigTree tree = ConfigTree::FromCommandLine("stack: {rotors: 8}", {summary}, {});
  ParamReader root = tree.Reader();
  Stack loaded;
  root.ReadSection("stack", &loaded);
  root.RejectUnknownKeys();  // no "command", "status" or "timing" sections
  EXPECT_EQ(DumpYaml(loaded), DumpYaml(stack));
}

TEST_F(SummaryAsConfigTest, ErrorsInASummaryNameTheFileAndLine) {
  const std::string summary =
      WriteFile("summary.json",
                "{\"command\": \"sim\",\n \"config\": {\"stack\": {\"rotors\": \"four\"}}}\n");
  const ConfigTree tree = ConfigTree::FromCommandLine("", {summary}, {});
  ParamReader root = tree.Reader();
  Stack loaded;
  EXPECT_THAT(
      MessageOf([&] { root.ReadSection("stack", &loaded); }),
      AllOf(HasSubstr("summary.json:2:"), HasSubstr("stack.rotors"), HasSubstr("an integer")));
}

// A plain YAML file with a `config` key but no `command` is an ordinary configuration file.
TEST_F(SummaryAsConfigTest, OrdinaryFilesWithAConfigKeyMergeWhole) {
  const std::string file = WriteFile("plain.yaml", "config: {a: 1}\nother: 2\n");
  const ConfigTree tree = ConfigTree::FromCommandLine("", {file}, {});
  EXPECT_TRUE(tree.root()["other"]);
  EXPECT_TRUE(tree.root()["config"]);
}

TEST(ConfigTreePut, ReplacesTheSectionAndNamesItsSource) {
  ConfigTree tree = ConfigTree::FromCommandLine("stack: {rotors: 8, typo: 1}\nseed: 3", {}, {});
  tree.PutParams("stack", Stack{});
  ParamReader root = tree.Reader();
  Stack loaded;
  loaded.rotors = 0;
  root.ReadSection("stack", &loaded);  // typo is gone with the replaced section
  EXPECT_EQ(loaded.rotors, 4);
  EXPECT_TRUE(tree.root()["seed"]);
  tree.Put("stack", YAML::Load("{rotors: x}"), "effective configuration");
  ParamReader again = tree.Reader();
  EXPECT_THAT(MessageOf([&] { again.ReadSection("stack", &loaded); }),
              HasSubstr("effective configuration"));
}

}  // namespace
}  // namespace aperture::config
