// Values get the care files get (issue 18, item 1): every number finite and within the range of
// its unit, infinity only where it means "no limit", names in maps not invented by --set, and a
// mistake in a --set item is a usage error (config::UsageError, exit 2) while the same mistake in
// a file is bad data (std::invalid_argument, exit 1).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "config/config_tree.h"
#include "config/param_reader.h"
#include "config/usage_error.h"
#include "tests/support/message_of.h"

namespace aperture::config {
namespace {

using test_support::MessageOf;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

double ReadNumber(const ConfigTree& tree, const std::string& key, double value = 1.0) {
  ParamReader section = tree.Reader().Section("s");
  section.Read(key, &value);
  return value;
}

TEST(ValueChecks, NanAndHugeNumbersAreRejectedWithTheUsersText) {
  for (const std::string text : {".nan", "nan", "1e308", "-2e12", ".inf", "-inf"}) {
    const ConfigTree tree = ConfigTree::FromCommandLine("", {}, {"s.mass_kg=" + text});
    const std::string message = MessageOf<UsageError>([&] { ReadNumber(tree, "mass_kg"); });
    EXPECT_THAT(message, AllOf(HasSubstr("--set s.mass_kg=" + text), HasSubstr("'s.mass_kg'"),
                               HasSubstr("a finite number in [-1e12, 1e12]")))
        << text;
  }
  // The bound is readable, never a 309-digit number.
  const ConfigTree huge = ConfigTree::FromCommandLine("", {}, {"s.mass_kg=1e308"});
  EXPECT_THAT(MessageOf<UsageError>([&] { ReadNumber(huge, "mass_kg"); }),
              Not(HasSubstr("00000000000")));
  const ConfigTree fine = ConfigTree::FromCommandLine("", {}, {"s.mass_kg=-1e12"});
  EXPECT_EQ(ReadNumber(fine, "mass_kg"), -1e12);
}

TEST(ValueChecks, AnglesInDegreesStayWithinOneTurn) {
  const ConfigTree tree = ConfigTree::FromCommandLine(
      "", {}, {"s.roll_deg=361", "s.yaw_deg=-360", "s.rpy_deg=[0, 0, 400]"});
  EXPECT_THAT(
      MessageOf<UsageError>([&] { ReadNumber(tree, "roll_deg"); }),
      AllOf(HasSubstr("'s.roll_deg'"), HasSubstr("[-360, 360] degrees"), HasSubstr("'361'")));
  EXPECT_EQ(ReadNumber(tree, "yaw_deg"), -360.0);
  ParamReader section = tree.Reader().Section("s");
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
  EXPECT_THAT(MessageOf<UsageError>([&] { section.Read("rpy_deg", &rpy_deg); }),
              HasSubstr("'s.rpy_deg[2]'"));
}

TEST(ValueChecks, TheSameMistakeInAFileIsBadDataNotAUsageError) {
  ConfigTree tree;
  tree.MergeYaml("s:\n  mass_kg: .nan\n", "scenario.yaml");
  const std::string message = MessageOf<std::invalid_argument>([&] {
    try {
      ReadNumber(tree, "mass_kg");
    } catch (const UsageError&) {
      ADD_FAILURE() << "a file's value is bad data, not a usage error";
      throw;
    }
  });
  EXPECT_THAT(message, AllOf(HasSubstr("scenario.yaml:2:12"), HasSubstr("'.nan'")));
}

TEST(ValueChecks, InfinityOnlyWhereItMeansNoLimit) {
  const ConfigTree tree =
      ConfigTree::FromCommandLine("", {}, {"s.floor_m=-.inf", "s.gate=.inf", "s.gain=.inf"});
  // A field whose default is infinite (no floor) reads back its dumped value.
  EXPECT_EQ(ReadNumber(tree, "floor_m", -std::numeric_limits<double>::infinity()),
            -std::numeric_limits<double>::infinity());
  // ReadLimit: .inf documented as "no limit".
  ParamReader section = tree.Reader().Section("s");
  double gate = 22.46;
  section.ReadLimit("gate", &gate);
  EXPECT_TRUE(std::isinf(gate));
  // Anywhere else infinity is an error, and NaN is one even for a limit.
  EXPECT_THAT(MessageOf<UsageError>([&] { ReadNumber(tree, "gain"); }), HasSubstr("'.inf'"));
  const ConfigTree nan_gate = ConfigTree::FromCommandLine("", {}, {"s.gate=.nan"});
  ParamReader nan_section = nan_gate.Reader().Section("s");
  EXPECT_THAT(MessageOf<UsageError>([&] { nan_section.ReadLimit("gate", &gate); }),
              HasSubstr("or .inf/-.inf"));
}

TEST(ValueChecks, SetCannotInventANameInAMapOfNamedEntries) {
  ConfigTree tree;
  tree.MergeYaml("cameras:\n  front: {rate_hz: 30}\n  down: {rate_hz: 20}\n", "built-in defaults");
  tree.ApplySet("cameras.front.rate_hz=50");  // an existing camera: fine
  ParamReader cameras = tree.Reader().Section("cameras");
  EXPECT_NO_THROW(cameras.RejectEntriesCreatedBySet("camera"));

  tree.ApplySet("cameras.frnt.rate_hz=30");  // a typo: would silently add a third camera
  ParamReader typo = tree.Reader().Section("cameras");
  EXPECT_THAT(MessageOf<UsageError>([&] { typo.RejectEntriesCreatedBySet("camera"); }),
              AllOf(HasSubstr("--set cameras.frnt.rate_hz=30"), HasSubstr("unknown camera 'frnt'"),
                    HasSubstr("known: front, down"), HasSubstr("--config")));
}

TEST(ValueChecks, AFileMayAddANamedEntryAndSetThenChangesIt) {
  ConfigTree tree;
  tree.MergeYaml("cameras:\n  front: {rate_hz: 30}\n", "built-in defaults");
  tree.MergeYaml("cameras:\n  down: {rate_hz: 20}\n", "two_cameras.yaml");
  tree.ApplySet("cameras.down.rate_hz=25");
  ParamReader cameras = tree.Reader().Section("cameras");
  EXPECT_NO_THROW(cameras.RejectEntriesCreatedBySet("camera"));
}

TEST(ValueChecks, SetDeclaresAnEntryByItsDeclaringKeyOnly) {
  ConfigTree tree;
  tree.ApplySet("objects.crate.shape=box");     // declares crate
  tree.ApplySet("objects.crate.radius_m=0.2");  // changes it
  ParamReader declared = tree.Reader().Section("objects");
  EXPECT_NO_THROW(declared.RejectEntriesCreatedBySet("object", "shape"));
  EXPECT_THAT(MessageOf<UsageError>([&] { declared.RejectEntriesCreatedBySet("object"); }),
              HasSubstr("unknown object 'crate'"));  // without a declaring key: refused

  tree.ApplySet("objects.crat.radius_m=1");  // no shape: a typo of crate
  ParamReader typo = tree.Reader().Section("objects");
  EXPECT_THAT(MessageOf<UsageError>([&] { typo.RejectEntriesCreatedBySet("object", "shape"); }),
              AllOf(HasSubstr("--set objects.crat.radius_m=1"), HasSubstr("unknown object 'crat'"),
                    HasSubstr("known: crate"), HasSubstr("--set objects.crat.shape=")));
}

// Validators that name fields the way the code does (struct.field), as control::Require does.
struct InnerGainParams {
  double p_per_s = 1.0;
  void Validate() const {
    if (!(p_per_s >= 0.0)) throw std::invalid_argument("InnerGainParams.p_per_s must be >= 0");
  }
};
struct OuterLoopParams {
  InnerGainParams gains;
  double rate_hz = 10.0;
  void Validate() const {
    if (!(rate_hz > gains.p_per_s)) {
      throw std::invalid_argument("OuterLoopParams.rate_hz = " + std::to_string(rate_hz) +
                                  " must exceed InnerGainParams.p_per_s");
    }
  }
};

OuterLoopParams LoadLoop(const ConfigTree& tree) {
  ParamReader loop = tree.Reader().Section("loop");
  OuterLoopParams params;
  loop.Read("rate_hz", &params.rate_hz);
  ParamReader gains = loop.Section("gains");
  gains.Read("p_per_s", &params.gains.p_per_s);
  gains.Validate(params.gains);
  loop.Validate(params);
  return params;
}

TEST(ValueChecks, ValidationMessagesNameKeyPathsInsteadOfStructs) {
  ConfigTree file;
  file.MergeYaml("loop:\n  rate_hz: 1\n  gains: {p_per_s: 5}\n", "loop.yaml");
  // The outer check names both structs: each becomes the key path it was loaded from, and the
  // message starts at the first named value's line and column.
  EXPECT_EQ(MessageOf([&] { LoadLoop(file); }),
            "loop.yaml:2:12: loop.rate_hz = 1.000000 must exceed loop.gains.p_per_s");

  ConfigTree set;
  set.MergeYaml("loop:\n  rate_hz: 10\n", "built-in defaults");
  set.ApplySet("loop.gains.p_per_s=-1");
  EXPECT_EQ(MessageOf<UsageError>([&] { LoadLoop(set); }),
            "--set loop.gains.p_per_s=-1: loop.gains.p_per_s must be >= 0");
  // A check failing at a value no --set item set still names the items inside the section.
  set.ApplySet("loop.gains.p_per_s=20");
  EXPECT_THAT(MessageOf<UsageError>([&] { LoadLoop(set); }),
              AllOf(HasSubstr("loop.rate_hz = 10.000000 must exceed loop.gains.p_per_s"),
                    Not(HasSubstr("Params"))));
}

TEST(ValueChecks, MistakesInSetItemsAreUsageErrors) {
  ConfigTree tree;
  EXPECT_THAT(MessageOf<UsageError>([&] { tree.ApplySet("gap.roll_deg"); }),
              HasSubstr("key=value"));
  EXPECT_THAT(MessageOf<UsageError>([&] { tree.ApplySet("a..b=1"); }), HasSubstr("'a..b=1'"));
  tree.ApplySet("s.typo=1");
  ParamReader section = tree.Reader().Section("s");
  double value = 0.0;
  section.Read("value", &value);
  EXPECT_THAT(MessageOf<UsageError>([&] { section.RejectUnknownKeys(); }),
              AllOf(HasSubstr("--set s.typo=1"), HasSubstr("known keys: value")));
}

struct SpeedParams {
  double speed_mps = 1.0;
  void Validate() const {
    if (!(speed_mps > 0.0)) throw std::invalid_argument("speed_mps must be > 0");
  }
};

TEST(ValueChecks, ValidationOfASectionWithASetItemIsAUsageErrorNamingIt) {
  ConfigTree tree;
  tree.MergeYaml("s: {speed_mps: 2}\n", "built-in defaults");
  tree.ApplySet("s.speed_mps=-1");
  ParamReader section = tree.Reader().Section("s");
  SpeedParams params;
  section.Read("speed_mps", &params.speed_mps);
  EXPECT_THAT(MessageOf<UsageError>([&] { section.Validate(params); }),
              AllOf(HasSubstr("set on the command line: --set s.speed_mps=-1"),
                    HasSubstr("speed_mps must be > 0")));
}

}  // namespace
}  // namespace aperture::config
