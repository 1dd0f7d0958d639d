#include "perception/graph/front_end_registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "config/config_tree.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/serial_executor.h"
#include "perception/quality/image_quality_analyzer.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using test_support::MessageOf;

using ::testing::AllOf;
using ::testing::HasSubstr;

// A second front end for composition tests: reads image_quality's output.
class ExposureAlarmNode final : public Node {
 public:
  std::string Name() const override { return "exposure_alarm"; }
  std::vector<SlotSpec> Inputs() const override {
    return {MakeSlot<ImageQuality>("image_quality")};
  }
  std::vector<SlotSpec> Outputs() const override { return {MakeSlot<bool>("too_dark")}; }
  void Run(NodeContext& context) override {
    context.Set("too_dark", context.Get<ImageQuality>("image_quality").mean_intensity < 40.0);
  }
};

// Creates image_quality with one `--set`-style override, as `aperture run --set` would.
std::unique_ptr<Node> CreateWithSet(const FrontEndRegistry& registry, const std::string& item) {
  config::ConfigTree tree;
  tree.ApplySet(item);
  config::ParamReader params = tree.Reader().Section("image_quality");
  return registry.Create("image_quality", params);
}

FrontEndRegistry MakeRegistry() {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  registry.Register("exposure_alarm", "test node", [](config::ParamReader&, const FrontEndResources&) {
    return std::make_unique<ExposureAlarmNode>();
  });
  return registry;
}

TEST(FrontEndRegistry, BuiltinsIncludeImageQuality) {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  EXPECT_TRUE(registry.Contains("image_quality"));
  EXPECT_FALSE(registry.Description("image_quality").empty());
}

TEST(FrontEndRegistry, UnknownNameListsKnownNames) {
  const FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(
      MessageOf([&] { registry.Create("image_qualty"); }),
      AllOf(HasSubstr("'image_qualty'"), HasSubstr("image_quality"), HasSubstr("exposure_alarm")));
  EXPECT_THAT(MessageOf([&] {
                registry.BuildGraph({"image_quality", "no_such_front_end"});
              }),
              AllOf(HasSubstr("'no_such_front_end'"), HasSubstr("image_quality")));
}

TEST(FrontEndRegistry, RejectsDuplicateRegistrationAndRepeatedSelection) {
  FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(MessageOf([&] {
                registry.Register("image_quality", "again",
                                  [](config::ParamReader&, const FrontEndResources&) { return std::unique_ptr<Node>(); });
              }),
              HasSubstr("'image_quality'"));
  EXPECT_THAT(MessageOf([&] {
                registry.BuildGraph({"image_quality", "image_quality"});
              }),
              HasSubstr("listed twice"));
  EXPECT_THAT(MessageOf([&] { registry.BuildGraph({}); }), HasSubstr("image_quality"));
}

TEST(FrontEndRegistry, ComposesFrontEndsIntoOneGraphWithTheirParams) {
  const FrontEndRegistry registry = MakeRegistry();
  // Listed consumer first: the graph orders by data, not by the list.
  config::ConfigTree tree;
  tree.ApplySet("image_quality.histogram_bins=32");
  tree.ApplySet("not_selected.anything=1");
  config::ParamReader root = tree.Reader();
  FrameGraph graph =
      registry.BuildGraph(SplitFrontEndList("exposure_alarm, image_quality"), root);
  // Sections of front ends that were not selected are left for the caller to judge.
  EXPECT_THAT(MessageOf([&] { root.RejectUnknownKeys(); }), HasSubstr("not_selected"));
  EXPECT_EQ(graph.TopologicalNames(),
            (std::vector<std::string>{"image_quality", "exposure_alarm"}));
  SerialExecutor executor(graph);
  Frame frame;
  frame.image = cv::Mat(48, 64, CV_8UC1, cv::Scalar(20));
  const FrameSlots slots = executor.Run(frame);
  EXPECT_TRUE(slots.Get<bool>("too_dark"));
  EXPECT_EQ(slots.Get<ImageQuality>("image_quality").histogram.size(), 32u);
}

TEST(FrontEndRegistry, MissingDependencyFrontEndIsAGraphError) {
  const FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(MessageOf([&] { registry.BuildGraph({"exposure_alarm"}); }),
              AllOf(HasSubstr("'exposure_alarm'"), HasSubstr("'image_quality'")));
}

TEST(FrontEndRegistry, UnknownOrBadParameterNamesTheKey) {
  const FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(MessageOf([&] { CreateWithSet(registry, "image_quality.histogram_bin=8"); }),
              AllOf(HasSubstr("--set image_quality.histogram_bin=8"),
                    HasSubstr("'image_quality.histogram_bin'"), HasSubstr("histogram_bins")));
  EXPECT_THAT(MessageOf([&] { CreateWithSet(registry, "image_quality.histogram_bins=8x"); }),
              AllOf(HasSubstr("'image_quality.histogram_bins'"), HasSubstr("'8x'")));
  EXPECT_THAT(MessageOf([&] { CreateWithSet(registry, "image_quality.histogram_bins=0"); }),
              HasSubstr("histogram_bins = 0"));
}

TEST(FrontEndResources, RequireCalibrationTellsTheUserToPassCalib) {
  const FrontEndResources none;
  EXPECT_THAT(MessageOf([&] { none.RequireCalibration("gap"); }),
              AllOf(HasSubstr("'gap'"), HasSubstr("--calib")));
}

TEST(SplitFrontEndList, TrimsAndRejectsEmptyEntries) {
  EXPECT_EQ(SplitFrontEndList(" a,b ,c"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(SplitFrontEndList("image_quality"), (std::vector<std::string>{"image_quality"}));
  EXPECT_THROW(SplitFrontEndList("a,,b"), std::invalid_argument);
  EXPECT_THROW(SplitFrontEndList("a,"), std::invalid_argument);
  EXPECT_THROW(SplitFrontEndList(""), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
