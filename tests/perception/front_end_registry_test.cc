#include "perception/graph/front_end_registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/param_reader.h"
#include "perception/graph/serial_executor.h"
#include "perception/quality/image_quality_analyzer.h"

namespace aperture::perception {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

template <typename Function>
std::string ErrorOf(Function&& function) {
  try {
    function();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "no std::invalid_argument thrown";
  return "";
}

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

FrontEndRegistry MakeRegistry() {
  FrontEndRegistry registry;
  RegisterBuiltinFrontEnds(registry);
  registry.Register("exposure_alarm", "test node", [](const NodeParams& params) {
    ParamReader(std::string("exposure_alarm"), params).CheckAllUsed();
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
      ErrorOf([&] { registry.Create("image_qualty"); }),
      AllOf(HasSubstr("'image_qualty'"), HasSubstr("image_quality"), HasSubstr("exposure_alarm")));
  EXPECT_THAT(ErrorOf([&] {
                registry.BuildGraph({"image_quality", "gap"});
              }),
              AllOf(HasSubstr("'gap'"), HasSubstr("image_quality")));
}

TEST(FrontEndRegistry, RejectsDuplicateRegistrationAndRepeatedSelection) {
  FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(ErrorOf([&] {
                registry.Register("image_quality", "again",
                                  [](const NodeParams&) { return std::unique_ptr<Node>(); });
              }),
              HasSubstr("'image_quality'"));
  EXPECT_THAT(ErrorOf([&] {
                registry.BuildGraph({"image_quality", "image_quality"});
              }),
              HasSubstr("listed twice"));
  EXPECT_THAT(ErrorOf([&] { registry.BuildGraph({}); }), HasSubstr("image_quality"));
}

TEST(FrontEndRegistry, ComposesFrontEndsIntoOneGraphWithTheirParams) {
  const FrontEndRegistry registry = MakeRegistry();
  // Listed consumer first: the graph orders by data, not by the list.
  FrameGraph graph = registry.BuildGraph(
      SplitFrontEndList("exposure_alarm, image_quality"),
      {{"image_quality", {{"histogram_bins", "32"}}}, {"not_selected", {{"anything", "1"}}}});
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
  EXPECT_THAT(ErrorOf([&] { registry.BuildGraph({"exposure_alarm"}); }),
              AllOf(HasSubstr("'exposure_alarm'"), HasSubstr("'image_quality'")));
}

TEST(FrontEndRegistry, UnknownOrBadParameterNamesTheKey) {
  const FrontEndRegistry registry = MakeRegistry();
  EXPECT_THAT(ErrorOf([&] {
                registry.Create("image_quality", {{"histogram_bin", "8"}});
              }),
              AllOf(HasSubstr("image_quality"), HasSubstr("'histogram_bin'"),
                    HasSubstr("'histogram_bins'")));
  EXPECT_THAT(ErrorOf([&] {
                registry.Create("image_quality", {{"histogram_bins", "8x"}});
              }),
              AllOf(HasSubstr("'histogram_bins'"), HasSubstr("'8x'")));
  EXPECT_THAT(ErrorOf([&] {
                registry.Create("image_quality", {{"histogram_bins", "0"}});
              }),
              HasSubstr("histogram_bins = 0"));
}

TEST(ParamReader, ParsesTypesAndFallsBackToDefaults) {
  const NodeParams params{{"gain", "2.5"}, {"count", "-3"}, {"enabled", "false"}, {"mode", "x"}};
  ParamReader reader("node", params);
  EXPECT_EQ(reader.Double("gain", 1.0), 2.5);
  EXPECT_EQ(reader.Int("count", 0), -3);
  EXPECT_FALSE(reader.Bool("enabled", true));
  EXPECT_EQ(reader.String("mode", "y"), "x");
  EXPECT_EQ(reader.Double("absent", 7.0), 7.0);
  EXPECT_NO_THROW(reader.CheckAllUsed());
  EXPECT_THAT(ErrorOf([&] { reader.Bool("mode", true); }), HasSubstr("'mode' = 'x'"));
  EXPECT_THAT(ErrorOf([&] { reader.Int("gain", 0); }), HasSubstr("'gain' = '2.5'"));
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
