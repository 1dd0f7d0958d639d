#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "config/config_tree.h"
#include "config/param_reader.h"
#include "tests/support/message_of.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::config {
namespace {

using test_support::MessageOf;

using ::testing::AllOf;
using ::testing::HasSubstr;

enum class BodyRateController { kProportional, kLqr };

struct DetectorParams {
  int pyramid_levels = 3;
  double threshold = 0.5;
};

struct TestParams {
  double mass_kg = 0.8;
  int rotors = 4;
  bool enabled = false;
  std::string name = "default";
  Eigen::Vector3d p_BC = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector3d> leds;
  BodyRateController body_rate = BodyRateController::kProportional;
  DetectorParams detector;
};

void LoadParams(ParamReader& reader, DetectorParams* params) {
  reader.Read("pyramid_levels", &params->pyramid_levels);
  reader.Read("threshold", &params->threshold);
  reader.RejectUnknownKeys();
}

void LoadParams(ParamReader& reader, TestParams* params) {
  reader.Read("mass_kg", &params->mass_kg);
  reader.Read("rotors", &params->rotors);
  reader.Read("enabled", &params->enabled);
  reader.Read("name", &params->name);
  reader.Read("p_BC", &params->p_BC);
  reader.Read("inertia_kgm2", &params->inertia_kgm2);
  reader.Read("leds", &params->leds);
  reader.ReadEnum(
      "body_rate", &params->body_rate,
      {{"proportional", BodyRateController::kProportional}, {"lqr", BodyRateController::kLqr}});
  reader.ReadSection("detector", &params->detector);
  reader.RejectUnknownKeys();
}

// Loads section "vehicle" of the tree the way a command would.
TestParams LoadVehicle(const ConfigTree& tree) {
  ParamReader root = tree.Reader();
  TestParams params;
  root.ReadSection("vehicle", &params);
  root.RejectUnknownKeys();
  return params;
}

class ConfigFileTest : public aperture::testing::TempDirectoryTest {};

TEST_F(ConfigFileTest, EmptyTreeKeepsStructDefaults) {
  const TestParams params = LoadVehicle(ConfigTree());
  const TestParams defaults;
  EXPECT_EQ(params.mass_kg, defaults.mass_kg);
  EXPECT_EQ(params.rotors, defaults.rotors);
  EXPECT_EQ(params.name, defaults.name);
  EXPECT_EQ(params.detector.pyramid_levels, defaults.detector.pyramid_levels);
}

TEST_F(ConfigFileTest, LayersApplyInOrderDefaultsFileSet) {
  const std::string file = WriteFile("vehicle.yaml",
                                     "vehicle:\n"
                                     "  mass_kg: 1.25\n"
                                     "  name: from_file\n"
                                     "  detector:\n"
                                     "    threshold: 0.75\n");
  const ConfigTree tree = ConfigTree::FromCommandLine(
      "vehicle: {mass_kg: 1.0, rotors: 6, name: from_defaults, detector: {pyramid_levels: 2}}",
      {file}, {"vehicle.name=from_set", "vehicle.detector.pyramid_levels=5"});
  const TestParams params = LoadVehicle(tree);
  EXPECT_EQ(params.mass_kg, 1.25);     // file beats defaults
  EXPECT_EQ(params.rotors, 6);         // defaults survive where nothing overrides them
  EXPECT_EQ(params.name, "from_set");  // --set beats file
  // Nested maps merge key by key: threshold from the file, levels from --set.
  EXPECT_EQ(params.detector.threshold, 0.75);
  EXPECT_EQ(params.detector.pyramid_levels, 5);
}

TEST_F(ConfigFileTest, LaterConfigFileWins) {
  const std::string first = WriteFile("a.yaml", "vehicle: {mass_kg: 1.0, rotors: 6}\n");
  const std::string second = WriteFile("b.yaml", "vehicle: {mass_kg: 2.0}\n");
  const TestParams params = LoadVehicle(ConfigTree::FromCommandLine("", {first, second}, {}));
  EXPECT_EQ(params.mass_kg, 2.0);
  EXPECT_EQ(params.rotors, 6);
}

TEST_F(ConfigFileTest, UnknownKeyNamesFileLineKeyAndKnownKeys) {
  const std::string file = WriteFile("typo.yaml",
                                     "vehicle:\n"
                                     "  mass_kg: 1.0\n"
                                     "  detector:\n"
                                     "    pyramid_levels: 2\n"
                                     "    treshold: 0.1\n");
  ConfigTree tree;
  tree.MergeFile(file);
  const std::string message = MessageOf([&] { LoadVehicle(tree); });
  // "treshold" is on line 5, column 5 (1-based).
  EXPECT_THAT(message, AllOf(HasSubstr(file + ":5:5"), HasSubstr("vehicle.detector.treshold"),
                             HasSubstr("pyramid_levels"), HasSubstr("threshold")));
}

TEST_F(ConfigFileTest, OverriddenUnknownKeyPointsAtTheLaterFile) {
  const std::string first = WriteFile("first.yaml", "vehicle: {extra: 1}\n");
  const std::string second = WriteFile("second.yaml", "# comment\n\nvehicle:\n  extra: 2\n");
  const std::string message = MessageOf([&] {
    LoadVehicle(ConfigTree::FromCommandLine("", {first, second}, {}));
  });
  EXPECT_THAT(message, HasSubstr(second + ":4:3"));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("first.yaml")));
}

TEST_F(ConfigFileTest, UnknownTopLevelSectionIsRejected) {
  ConfigTree tree;
  tree.MergeFile(WriteFile("top.yaml", "vehicle: {}\nvehicel: {mass_kg: 1}\n"));
  EXPECT_THAT(MessageOf([&] { LoadVehicle(tree); }),
              AllOf(HasSubstr("top.yaml:2:1"), HasSubstr("'vehicel'"), HasSubstr("vehicle")));
}

TEST_F(ConfigFileTest, UnknownKeyFromSetNamesTheSetItem) {
  const ConfigTree tree = ConfigTree::FromCommandLine("", {}, {"vehicle.mas_kg=2"});
  EXPECT_THAT(MessageOf([&] { LoadVehicle(tree); }),
              AllOf(HasSubstr("--set vehicle.mas_kg=2"), HasSubstr("mass_kg")));
}

TEST_F(ConfigFileTest, WrongTypeNamesFileLineKeyAndExpectedType) {
  const std::string file = WriteFile("type.yaml", "vehicle:\n  rotors: 4\n  mass_kg: heavy\n");
  ConfigTree tree;
  tree.MergeFile(file);
  EXPECT_THAT(MessageOf([&] { LoadVehicle(tree); }),
              AllOf(HasSubstr(file + ":3:12"), HasSubstr("vehicle.mass_kg"), HasSubstr("a number"),
                    HasSubstr("'heavy'")));
}

TEST_F(ConfigFileTest, WrongTypeFromSetKeepsSetLocationAfterFileMerge) {
  // The file supplies vehicle.rotors; --set overrides it with a bad value: the error must point at
  // the --set item, not at the file line the key used to come from.
  const std::string file = WriteFile("ok.yaml", "vehicle:\n  rotors: 4\n");
  const ConfigTree tree = ConfigTree::FromCommandLine("", {file}, {"vehicle.rotors=2.5"});
  const std::string message = MessageOf([&] { LoadVehicle(tree); });
  EXPECT_THAT(message, AllOf(HasSubstr("--set vehicle.rotors=2.5"), HasSubstr("an integer")));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("ok.yaml")));
}

TEST_F(ConfigFileTest, ScalarTypesAreStrict) {
  const auto load = [](const std::string& yaml) {
    ConfigTree tree;
    tree.MergeYaml(yaml, "inline");
    return LoadVehicle(tree);
  };
  EXPECT_THAT(MessageOf([&] { load("vehicle: {rotors: 4x}"); }), HasSubstr("an integer"));
  EXPECT_THAT(MessageOf([&] { load("vehicle: {enabled: 1}"); }), HasSubstr("a boolean"));
  EXPECT_THAT(MessageOf([&] { load("vehicle: {name: [a, b]}"); }), HasSubstr("a string"));
  EXPECT_THAT(MessageOf([&] { load("vehicle: {mass_kg: }"); }), HasSubstr("null"));
  EXPECT_THAT(MessageOf([&] { load("vehicle: {detector: 3}"); }), HasSubstr("must be a map"));
  const TestParams params = load("vehicle: {enabled: true, mass_kg: 1e-1, rotors: -2}");
  EXPECT_TRUE(params.enabled);
  EXPECT_EQ(params.mass_kg, 0.1);
  EXPECT_EQ(params.rotors, -2);
  EXPECT_THAT(MessageOf([&] { load("vehicle: {mass_kg: .nan}"); }), HasSubstr("a finite number"));
}

TEST_F(ConfigFileTest, MalformedSetItemsNameTheItem) {
  ConfigTree tree;
  EXPECT_THAT(MessageOf([&] { tree.ApplySet("gap.roll_deg"); }),
              AllOf(HasSubstr("gap.roll_deg"), HasSubstr("key=value")));
  EXPECT_THAT(MessageOf([&] { tree.ApplySet("=3"); }), HasSubstr("'=3'"));
  EXPECT_THAT(MessageOf([&] { tree.ApplySet("gap..roll=3"); }), HasSubstr("gap..roll=3"));
  EXPECT_THAT(MessageOf([&] { tree.ApplySet("gap.roll=[1,2"); }), HasSubstr("gap.roll=[1,2"));
}

TEST_F(ConfigFileTest, InvalidYamlFileNamesFileAndLine) {
  const std::string file = WriteFile("broken.yaml", "vehicle:\n  mass_kg: [1, 2\n");
  ConfigTree tree;
  EXPECT_THAT(MessageOf([&] { tree.MergeFile(file); }), HasSubstr(file + ":"));
  EXPECT_THROW(tree.MergeFile((directory_ / "missing.yaml").string()), std::runtime_error);
}

TEST_F(ConfigFileTest, VectorsMatricesAndSequencesFromFileAndSet) {
  const std::string file = WriteFile("geometry.yaml",
                                     "vehicle:\n"
                                     "  p_BC: [0.1, -0.2, 0.3]\n"
                                     "  inertia_kgm2: [[1, 2, 3], [4, 5, 6], [7, 8, 9]]\n");
  const TestParams from_file = LoadVehicle(ConfigTree::FromCommandLine("", {file}, {}));
  EXPECT_EQ(from_file.p_BC, Eigen::Vector3d(0.1, -0.2, 0.3));
  Eigen::Matrix3d expected;
  expected << 1, 2, 3, 4, 5, 6, 7, 8, 9;  // rows as written
  EXPECT_EQ(from_file.inertia_kgm2, expected);

  const TestParams from_set = LoadVehicle(ConfigTree::FromCommandLine(
      "", {file}, {"vehicle.leds=[[0,0,0],[1,0,0]]", "vehicle.inertia_kgm2=[9,8,7,6,5,4,3,2,1]"}));
  ASSERT_EQ(from_set.leds.size(), 2u);
  EXPECT_EQ(from_set.leds[1], Eigen::Vector3d(1, 0, 0));
  Eigen::Matrix3d flat;
  flat << 9, 8, 7, 6, 5, 4, 3, 2, 1;  // flat lists are row-major
  EXPECT_EQ(from_set.inertia_kgm2, flat);

  EXPECT_THAT(
      MessageOf([&] { LoadVehicle(ConfigTree::FromCommandLine("", {}, {"vehicle.p_BC=[1,2]"})); }),
      AllOf(HasSubstr("vehicle.p_BC"), HasSubstr("3 numbers")));
  EXPECT_THAT(MessageOf([&] {
                LoadVehicle(ConfigTree::FromCommandLine("", {}, {"vehicle.leds=[[0,0,x]]"}));
              }),
              HasSubstr("vehicle.leds[0][2]"));
}

TEST_F(ConfigFileTest, EnumsMapNamesAndListAllowedValues) {
  EXPECT_EQ(LoadVehicle(ConfigTree::FromCommandLine("", {}, {"vehicle.body_rate=lqr"})).body_rate,
            BodyRateController::kLqr);
  const std::string file = WriteFile("enum.yaml", "vehicle:\n  body_rate: pid\n");
  EXPECT_THAT(MessageOf([&] { LoadVehicle(ConfigTree::FromCommandLine("", {file}, {})); }),
              AllOf(HasSubstr(file + ":2:14"), HasSubstr("'pid'"), HasSubstr("proportional, lqr")));
}

TEST_F(ConfigFileTest, SetReplacesScalarParentWithMap) {
  ConfigTree tree;
  tree.MergeYaml("vehicle: 3\n", "inline");
  tree.ApplySet("vehicle.mass_kg=2.5");
  EXPECT_EQ(LoadVehicle(tree).mass_kg, 2.5);
  EXPECT_THAT(tree.ToYaml(), HasSubstr("mass_kg: 2.5"));
}

TEST_F(ConfigFileTest, UnsignedAndFloatFields) {
  ParamReader reader(YAML::Load("seed: 4294967295\ncount: 12\ngain: 0.25\nbad: -1\n"), "inline");
  unsigned int seed = 0;
  std::size_t count = 0;
  float gain = 0.0f;
  reader.Read("seed", &seed);
  reader.Read("count", &count);
  reader.Read("gain", &gain);
  EXPECT_EQ(seed, 4294967295u);
  EXPECT_EQ(count, 12u);
  EXPECT_EQ(gain, 0.25f);
  std::size_t bad = 0;
  EXPECT_THAT(MessageOf([&] { reader.Read("bad", &bad); }), HasSubstr("non-negative integer"));
}

TEST_F(ConfigFileTest, ToJsonTypesScalarsAndKeepsQuotedStrings) {
  ConfigTree tree;
  tree.MergeYaml("a: {b: 1, c: x, d: +.5, e: '3'}\nf: [true, ~, \"q\\\"s\", .nan]\n", "inline");
  tree.ApplySet("g=1e3");
  EXPECT_EQ(tree.ToJson(),
            R"({"a":{"b":1,"c":"x","d":0.5,"e":"3"},"f":[true,null,"q\"s",".nan"],"g":1000})");
}

// 64-bit seeds (SetSeed derives them by hashing) must come back exactly from summary.json: every
// integer of the uint64/int64 range is written as an integer, not a rounded double.
TEST_F(ConfigFileTest, ToJsonKeepsSixtyFourBitIntegersExact) {
  ConfigTree tree;
  tree.MergeYaml(
      "max: 18446744073709551615\nseed: 13787848793156545019\nlow: -9223372036854775808\n"
      "huge: 99999999999999999999\n",
      "inline");
  EXPECT_EQ(tree.ToJson(), R"({"max":18446744073709551615,"seed":13787848793156545019,)"
                           R"("low":-9223372036854775808,"huge":1e+20})");
  std::uint64_t seed = 0;
  ParamReader(YAML::Load(tree.ToJson()), "json").Read("seed", &seed);
  EXPECT_EQ(seed, 13787848793156545019ull);
}

TEST_F(ConfigFileTest, StandaloneReaderNamesItsSource) {
  ParamReader reader(YAML::Load("mass_kg: 1\nextra: 2\n"), "inline.yaml");
  TestParams params;
  reader.Read("mass_kg", &params.mass_kg);
  EXPECT_EQ(params.mass_kg, 1.0);
  EXPECT_THAT(MessageOf([&] { reader.RejectUnknownKeys(); }),
              AllOf(HasSubstr("inline.yaml:2:1"), HasSubstr("'extra'")));
}

TEST_F(ConfigFileTest, KeysListsUserNamedEntriesInDocumentOrder) {
  ParamReader reader(YAML::Load("objects: {zeta: 1, alpha: 2, mid: 3}\n"), "inline.yaml");
  EXPECT_EQ(reader.Section("objects").Keys(), (std::vector<std::string>{"zeta", "alpha", "mid"}));
  EXPECT_TRUE(reader.Section("absent").Keys().empty());
}

struct MassParams {
  double mass_kg = 1.0;
  void Validate() const {
    if (!(mass_kg > 0.0)) throw std::invalid_argument("mass_kg must be > 0");
  }
};

TEST(ParamReaderValidate, NamesTheSectionAndWhereItCameFrom) {
  ConfigTree tree;
  tree.ApplySet("vehicle.mass_kg=-2");
  ParamReader vehicle = tree.Reader().Section("vehicle");
  MassParams params;
  vehicle.Read("mass_kg", &params.mass_kg);
  try {
    vehicle.Validate(params);
    FAIL() << "a negative mass must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("--set vehicle.mass_kg=-2"),
                                HasSubstr("section 'vehicle'"), HasSubstr("mass_kg must be > 0")));
  }
  params.mass_kg = 0.5;
  EXPECT_NO_THROW(vehicle.Validate(params));
}

}  // namespace
}  // namespace aperture::config
