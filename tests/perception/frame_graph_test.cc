#include "perception/graph/frame_graph.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "perception/graph/parallel_executor.h"
#include "perception/graph/serial_executor.h"
#include "perception/graph/timing_stats.h"
#include "perception/sensor_data.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

// A node whose behaviour is given by a function: lets each test build its own graph shape.
class FunctionNode final : public Node {
 public:
  FunctionNode(std::string name, std::vector<SlotSpec> inputs, std::vector<SlotSpec> outputs,
               std::function<void(NodeContext&)> run = {},
               std::function<std::map<std::string, double>(const NodeContext&)> metrics = {})
      : name_(std::move(name)),
        inputs_(std::move(inputs)),
        outputs_(std::move(outputs)),
        run_(std::move(run)),
        metrics_(std::move(metrics)) {}

  std::string Name() const override { return name_; }
  std::vector<SlotSpec> Inputs() const override { return inputs_; }
  std::vector<SlotSpec> Outputs() const override { return outputs_; }
  void Run(NodeContext& context) override {
    if (run_) run_(context);
  }
  std::map<std::string, double> Metrics(const NodeContext& context) const override {
    return metrics_ ? metrics_(context) : std::map<std::string, double>{};
  }
  void DrawOverlay(const NodeContext&, cv::Mat& bgr) const override {
    // Records the drawing order in the image: one pixel per call, row 0, column = call number.
    int column = 0;
    while (bgr.at<cv::Vec3b>(0, column)[0] != 0) ++column;
    bgr.at<cv::Vec3b>(0, column) = cv::Vec3b(static_cast<uint8_t>(name_[0]), 0, 0);
  }

 private:
  std::string name_;
  std::vector<SlotSpec> inputs_;
  std::vector<SlotSpec> outputs_;
  std::function<void(NodeContext&)> run_;
  std::function<std::map<std::string, double>(const NodeContext&)> metrics_;
};

template <typename... Nodes>
std::vector<std::unique_ptr<Node>> MakeNodes(Nodes... nodes) {
  std::vector<std::unique_ptr<Node>> list;
  (list.push_back(std::make_unique<FunctionNode>(std::move(nodes))), ...);
  return list;
}

// Returns the message of the std::invalid_argument that building the graph throws.
std::string BuildError(std::vector<std::unique_ptr<Node>> nodes) {
  return test_support::MessageOf([&] { FrameGraph graph(std::move(nodes)); });
}

TEST(FrameGraphValidation, MissingProducerNamesConsumerAndSlot) {
  const std::string message = BuildError(MakeNodes(
      FunctionNode("blur", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("blurred")}),
      FunctionNode("edge_count", {MakeSlot<cv::Mat>("edges")}, {MakeSlot<double>("count")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'edge_count'"), HasSubstr("'edges'"),
                             HasSubstr("no node produces")));
}

TEST(FrameGraphValidation, TypeMismatchNamesProducerConsumerSlotAndTypes) {
  const std::string message = BuildError(
      MakeNodes(FunctionNode("blur", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("blurred")}),
                FunctionNode("stats", {MakeSlot<double>("blurred")}, {MakeSlot<double>("mean")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'blur'"), HasSubstr("'stats'"), HasSubstr("'blurred'"),
                             HasSubstr("cv::Mat"), HasSubstr("double")));
}

TEST(FrameGraphValidation, FrameReadWithWrongTypeIsAMismatchWithTheSource) {
  const std::string message = BuildError(
      MakeNodes(FunctionNode("reader", {MakeSlot<cv::Mat>("frame")}, {MakeSlot<int>("n")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'reader'"), HasSubstr("'frame'"), HasSubstr("<source>")));
}

TEST(FrameGraphValidation, DuplicateProducerNamesBothNodesAndSlot) {
  const std::string message = BuildError(
      MakeNodes(FunctionNode("left", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("mask")}),
                FunctionNode("middle", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("other")}),
                FunctionNode("right", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("mask")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'left'"), HasSubstr("'right'"), HasSubstr("'mask'"),
                             HasSubstr("two producers"), Not(HasSubstr("'middle'"))));
}

TEST(FrameGraphValidation, NodeWritingTheFrameSlotClashesWithTheSource) {
  const std::string message =
      BuildError(MakeNodes(FunctionNode("rewriter", {}, {MakeSlot<Frame>("frame")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'rewriter'"), HasSubstr("'frame'"), HasSubstr("<source>")));
}

TEST(FrameGraphValidation, CycleNamesTheNodesOnIt) {
  const std::string message = BuildError(MakeNodes(
      FunctionNode("independent", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("z")}),
      FunctionNode("a", {MakeSlot<Frame>("frame"), MakeSlot<int>("y")}, {MakeSlot<int>("x")}),
      FunctionNode("b", {MakeSlot<int>("x")}, {MakeSlot<int>("y")})));
  EXPECT_THAT(message, HasSubstr("cycle"));
  // The path is printed producer -> consumer and closes on its first node.
  EXPECT_THAT(message, HasSubstr("'b' -> 'a' -> 'b'"));
  EXPECT_THAT(message, Not(HasSubstr("independent")));
}

TEST(FrameGraphValidation, NodeReadingItsOwnOutputIsACycle) {
  const std::string message = BuildError(
      MakeNodes(FunctionNode("loop", {MakeSlot<int>("state")}, {MakeSlot<int>("state")})));
  EXPECT_THAT(message, HasSubstr("'loop' -> 'loop'"));
}

TEST(FrameGraphValidation, DuplicateNodeNames) {
  const std::string message =
      BuildError(MakeNodes(FunctionNode("same", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("a")}),
                           FunctionNode("same", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("b")})));
  EXPECT_THAT(message, AllOf(HasSubstr("'same'"), HasSubstr("unique")));
}

TEST(FrameGraph, TopologicalOrderIsStableAndRespectsDependencies) {
  // Inserted consumers first: the order must follow the data, ties by insertion index.
  FrameGraph graph(MakeNodes(
      FunctionNode("join", {MakeSlot<int>("a"), MakeSlot<int>("b")}, {MakeSlot<int>("sum")}),
      FunctionNode("second", {MakeSlot<int>("a")}, {MakeSlot<int>("b")}),
      FunctionNode("first", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("a")}),
      FunctionNode("other", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("c")})));
  // Ready at start: first(2), other(3); first frees second(1), which frees join(0); both have
  // lower indices than other, so they run before it.
  EXPECT_EQ(graph.TopologicalNames(),
            (std::vector<std::string>{"first", "second", "join", "other"}));
  EXPECT_EQ(graph.dependencies(0), (std::vector<std::size_t>{1, 2}));
  EXPECT_TRUE(graph.dependencies(2).empty());
}

TEST(FrameGraph, EmptyGraphRunsAndKeepsTheFrame) {
  FrameGraph graph({});
  SerialExecutor executor(graph);
  Frame frame;
  frame.index = 7;
  const FrameSlots slots = executor.Run(frame);
  EXPECT_EQ(slots.Get<Frame>("frame").index, 7);
}

TEST(NodeContext, AccessOutsideTheDeclarationOrWithTheWrongTypeThrowsNamingNodeAndSlot) {
  auto run_and_get_error = [](std::function<void(NodeContext&)> body) -> std::string {
    FrameGraph graph(
        MakeNodes(FunctionNode("producer", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("count")}),
                  FunctionNode("user", {MakeSlot<int>("count")}, {MakeSlot<double>("ratio")},
                               std::move(body))));
    SerialExecutor executor(graph);
    try {
      executor.Run(Frame{});
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  };
  // "producer" never sets "count": reading it names the slot.
  EXPECT_THAT(run_and_get_error([](NodeContext& c) { c.Get<int>("count"); }),
              AllOf(HasSubstr("user"), HasSubstr("'count'"), HasSubstr("no value")));
  EXPECT_THAT(run_and_get_error([](NodeContext& c) { c.Get<Frame>("frame"); }),
              AllOf(HasSubstr("'user'"), HasSubstr("'frame'"), HasSubstr("Inputs()")));
  EXPECT_THAT(run_and_get_error([](NodeContext& c) { c.Set<double>("count", 1.0); }),
              AllOf(HasSubstr("'user'"), HasSubstr("'count'"), HasSubstr("Outputs()")));
  EXPECT_THAT(
      run_and_get_error([](NodeContext& c) { c.Set<float>("ratio", 1.0f); }),
      AllOf(HasSubstr("user"), HasSubstr("'ratio'"), HasSubstr("double"), HasSubstr("float")));
}

// ---- Serial and parallel executors on a graph with independent branches and a join ----

struct PipelineOutputs {
  cv::Mat blurred;
  cv::Mat gradient;
  cv::Mat detail;
  std::vector<double> profile;
  double score = 0.0;
};

// The same computations as the graph below, written out directly: ground truth for the graph.
PipelineOutputs ComputeDirectly(const cv::Mat& image) {
  PipelineOutputs out;
  cv::GaussianBlur(image, out.blurred, cv::Size(7, 7), 1.5);
  cv::Mat gx, gy;
  cv::Sobel(image, gx, CV_32F, 1, 0);
  cv::Sobel(image, gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, out.gradient);
  cv::Laplacian(out.blurred, out.detail, CV_32F);
  cv::Mat column_sums;
  cv::reduce(image, column_sums, 0, cv::REDUCE_SUM, CV_64F);
  column_sums.copyTo(out.profile);
  out.score = cv::sum(out.gradient)[0] + cv::norm(out.detail, cv::NORM_L1) +
              *std::max_element(out.profile.begin(), out.profile.end());
  return out;
}

// frame -> blur -> detail ─┐
// frame -> gradient ───────┼─> score (join)
// frame -> profile ────────┘
std::vector<std::unique_ptr<Node>> MakePipelineNodes() {
  return MakeNodes(
      FunctionNode(
          "score",
          {MakeSlot<cv::Mat>("gradient"), MakeSlot<cv::Mat>("detail"),
           MakeSlot<std::vector<double>>("profile")},
          {MakeSlot<double>("score")},
          [](NodeContext& c) {
            const auto& profile = c.Get<std::vector<double>>("profile");
            c.Set("score", cv::sum(c.Get<cv::Mat>("gradient"))[0] +
                               cv::norm(c.Get<cv::Mat>("detail"), cv::NORM_L1) +
                               *std::max_element(profile.begin(), profile.end()));
          },
          [](const NodeContext& c) {
            return std::map<std::string, double>{{"value", c.Get<double>("score")}};
          }),
      FunctionNode("blur", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("blurred")},
                   [](NodeContext& c) {
                     cv::Mat blurred;
                     cv::GaussianBlur(c.Get<Frame>("frame").image, blurred, cv::Size(7, 7), 1.5);
                     c.Set("blurred", blurred);
                   }),
      FunctionNode("gradient", {MakeSlot<Frame>("frame")}, {MakeSlot<cv::Mat>("gradient")},
                   [](NodeContext& c) {
                     cv::Mat gx, gy, magnitude;
                     cv::Sobel(c.Get<Frame>("frame").image, gx, CV_32F, 1, 0);
                     cv::Sobel(c.Get<Frame>("frame").image, gy, CV_32F, 0, 1);
                     cv::magnitude(gx, gy, magnitude);
                     c.Set("gradient", magnitude);
                   }),
      FunctionNode(
          "detail", {MakeSlot<cv::Mat>("blurred")}, {MakeSlot<cv::Mat>("detail")},
          [](NodeContext& c) {
            cv::Mat detail;
            cv::Laplacian(c.Get<cv::Mat>("blurred"), detail, CV_32F);
            c.Set("detail", detail);
          },
          [](const NodeContext& c) {
            return std::map<std::string, double>{
                {"l1", cv::norm(c.Get<cv::Mat>("detail"), cv::NORM_L1)}};
          }),
      FunctionNode("profile", {MakeSlot<Frame>("frame")},
                   {MakeSlot<std::vector<double>>("profile")}, [](NodeContext& c) {
                     cv::Mat column_sums;
                     cv::reduce(c.Get<Frame>("frame").image, column_sums, 0, cv::REDUCE_SUM,
                                CV_64F);
                     std::vector<double> profile;
                     column_sums.copyTo(profile);
                     c.Set("profile", profile);
                   }));
}

std::vector<Frame> MakeFrames(int count) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> coordinate(0, 150);
  std::vector<Frame> frames;
  for (int i = 0; i < count; ++i) {
    Frame frame;
    frame.index = i;
    frame.t_s = 0.01 * i;
    frame.image = cv::Mat(120, 160, CV_8UC1);
    cv::randu(frame.image, 0, 80);
    for (int k = 0; k < 5; ++k) {
      cv::rectangle(frame.image, cv::Rect(coordinate(rng), coordinate(rng) % 110, 25, 15),
                    cv::Scalar(120 + 25 * k), cv::FILLED);
    }
    frames.push_back(frame);
  }
  return frames;
}

double MaxAbsDifference(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() ? cv::norm(a, b, cv::NORM_INF) : 1e300;
}

TEST(FrameGraphExecutors, SerialAndParallelGiveIdenticalOutputsEqualToDirectComputation) {
  constexpr int kFrames = 60;
  FrameGraph serial_graph(MakePipelineNodes());
  FrameGraph parallel_graph(MakePipelineNodes());
  SerialExecutor serial(serial_graph);
  // More workers than independent branches, so the branches can overlap.
  ParallelExecutor parallel(parallel_graph, ParallelExecutorParams{4});
  FrameSlots serial_slots = serial_graph.MakeSlots(Frame{});
  FrameSlots parallel_slots = parallel_graph.MakeSlots(Frame{});
  for (const Frame& frame : MakeFrames(kFrames)) {
    serial.Run(frame, serial_slots);
    parallel.Run(frame, parallel_slots);
    // Same operations on the same data: bit-identical, so compare with zero tolerance.
    for (const char* slot : {"blurred", "gradient", "detail"}) {
      EXPECT_EQ(
          MaxAbsDifference(serial_slots.Get<cv::Mat>(slot), parallel_slots.Get<cv::Mat>(slot)), 0.0)
          << slot << " frame " << frame.index;
    }
    EXPECT_EQ(serial_slots.Get<std::vector<double>>("profile"),
              parallel_slots.Get<std::vector<double>>("profile"));
    EXPECT_EQ(serial_slots.Get<double>("score"), parallel_slots.Get<double>("score"));
    EXPECT_EQ(serial_graph.CollectMetrics(serial_slots),
              parallel_graph.CollectMetrics(parallel_slots));

    const PipelineOutputs direct = ComputeDirectly(frame.image);
    EXPECT_EQ(MaxAbsDifference(direct.detail, parallel_slots.Get<cv::Mat>("detail")), 0.0);
    EXPECT_EQ(direct.profile, parallel_slots.Get<std::vector<double>>("profile"));
    EXPECT_EQ(direct.score, parallel_slots.Get<double>("score"));
  }
}

TEST(FrameGraphExecutors, TimingHasOneEntryPerFrameForEveryNodeInTopologicalOrder) {
  constexpr int kFrames = 25;
  FrameGraph graph(MakePipelineNodes());
  ParallelExecutor executor(graph);
  for (const Frame& frame : MakeFrames(kFrames)) executor.Run(frame);
  const std::vector<NodeTiming> timing = executor.Timing();
  ASSERT_EQ(timing.size(), graph.size());
  for (std::size_t i = 0; i < timing.size(); ++i) {
    EXPECT_EQ(timing[i].node, graph.TopologicalNames()[i]);
    EXPECT_EQ(timing[i].stats.count, kFrames);
    EXPECT_GT(timing[i].stats.max_s, 0.0);
    EXPECT_LE(timing[i].stats.median_s, timing[i].stats.p95_s);
    EXPECT_LE(timing[i].stats.p95_s, timing[i].stats.max_s);
  }
  EXPECT_EQ(executor.FrameTiming().count, kFrames);
}

TEST(FrameGraphExecutors, CollectMetricsPrefixesNodeNames) {
  FrameGraph graph(MakePipelineNodes());
  SerialExecutor executor(graph);
  const Frame frame = MakeFrames(1).front();
  const FrameSlots slots = executor.Run(frame);
  const std::map<std::string, double> metrics = graph.CollectMetrics(slots);
  const PipelineOutputs direct = ComputeDirectly(frame.image);
  ASSERT_EQ(metrics.size(), 2u);
  EXPECT_EQ(metrics.at("score.value"), direct.score);
  EXPECT_EQ(metrics.at("detail.l1"), cv::norm(direct.detail, cv::NORM_L1));
}

TEST(FrameGraphExecutors, OverlaysAreDrawnInTopologicalOrder) {
  FrameGraph graph(MakePipelineNodes());
  SerialExecutor executor(graph);
  const FrameSlots slots = executor.Run(MakeFrames(1).front());
  cv::Mat bgr(4, 8, CV_8UC3, cv::Scalar::all(0));
  graph.DrawOverlays(slots, bgr);
  std::string drawn;
  for (int column = 0; column < 5; ++column) {
    drawn += static_cast<char>(bgr.at<cv::Vec3b>(0, column)[0]);
  }
  // Topological order: blur, gradient, detail, profile, score -> first letters.
  EXPECT_EQ(graph.TopologicalNames(),
            (std::vector<std::string>{"blur", "gradient", "detail", "profile", "score"}));
  EXPECT_EQ(drawn, "bgdps");
}

TEST(FrameGraphExecutors, RenderOverlayExpandsGrayFramesAndDraws) {
  FrameGraph graph(MakePipelineNodes());
  SerialExecutor executor(graph);
  // Row 0 black: FunctionNode's overlay marks its drawing order there (see DrawOverlay).
  Frame frame;
  frame.image = cv::Mat(60, 80, CV_8UC1, cv::Scalar(0));
  cv::rectangle(frame.image, cv::Rect(10, 10, 40, 30), cv::Scalar(90), cv::FILLED);
  const FrameSlots slots = executor.Run(frame);
  const cv::Mat overlay = graph.RenderOverlay(slots);
  ASSERT_EQ(overlay.type(), CV_8UC3);
  ASSERT_EQ(overlay.size(), frame.image.size());
  // FunctionNode draws only into row 0; below it every channel equals the gray frame.
  cv::Mat channels[3];
  cv::split(overlay, channels);
  const cv::Rect below(0, 1, frame.image.cols, frame.image.rows - 1);
  for (const cv::Mat& channel : channels) {
    EXPECT_EQ(cv::norm(channel(below), frame.image(below), cv::NORM_INF), 0.0);
  }
  EXPECT_EQ(overlay.at<cv::Vec3b>(0, 0)[0], 'b');
}

// Two independent nodes meet at a rendezvous: each announces itself and waits for the other. Run
// serially, the first would wait alone until the deadline. The deadline is a safety net against a
// hang, not a measured duration; the test needs two hardware threads.
TEST(FrameGraphExecutors, ParallelExecutorRunsIndependentNodesConcurrently) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs two hardware threads";
  std::atomic<int> arrived{0};
  auto rendezvous = [&arrived](NodeContext& context) {
    ++arrived;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (arrived.load() < 2 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::yield();
    }
    context.Set(context.node_name(), arrived.load() == 2);
  };
  FrameGraph graph(MakeNodes(
      FunctionNode("left", {MakeSlot<Frame>("frame")}, {MakeSlot<bool>("left")}, rendezvous),
      FunctionNode("right", {MakeSlot<Frame>("frame")}, {MakeSlot<bool>("right")}, rendezvous)));
  ParallelExecutor executor(graph, ParallelExecutorParams{2});
  const FrameSlots slots = executor.Run(Frame{});
  EXPECT_TRUE(slots.Get<bool>("left"));
  EXPECT_TRUE(slots.Get<bool>("right"));
}

TEST(FrameGraphExecutors, ParallelExecutorRethrowsTheFirstNodeErrorAndSkipsDependents) {
  int dependent_runs = 0;
  FrameGraph graph(
      MakeNodes(FunctionNode("failing", {MakeSlot<Frame>("frame")}, {MakeSlot<int>("x")},
                             [](NodeContext&) { throw std::runtime_error("sensor glitch"); }),
                FunctionNode("dependent", {MakeSlot<int>("x")}, {MakeSlot<int>("y")},
                             [&dependent_runs](NodeContext&) { ++dependent_runs; })));
  ParallelExecutor executor(graph);
  EXPECT_THROW(
      {
        try {
          executor.Run(Frame{});
        } catch (const std::runtime_error& error) {
          EXPECT_STREQ(error.what(), "sensor glitch");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_EQ(dependent_runs, 0);
  // The executor stays usable after a failed frame.
  EXPECT_THROW(executor.Run(Frame{}), std::runtime_error);
  EXPECT_EQ(dependent_runs, 0);
}

// Reports the frame time as the x translation of a pose on stream "clock", every other frame.
class PoseNode final : public Node {
 public:
  std::string Name() const override { return "pose_node"; }
  std::vector<SlotSpec> Inputs() const override { return {MakeSlot<Frame>(kFrameSlot)}; }
  std::vector<SlotSpec> Outputs() const override { return {MakeSlot<double>("t")}; }
  void Run(NodeContext& context) override {
    context.Set("t", context.Get<Frame>(kFrameSlot).t_s);
  }
  std::vector<PoseObservation> Poses(const NodeContext& context) const override {
    const Frame& frame = context.Get<Frame>(kFrameSlot);
    if (frame.index % 2 == 1) return {};
    PoseObservation pose;
    pose.stream = "clock";
    pose.t_s = frame.t_s;
    pose.T_CX.translation().x() = context.Get<double>("t");
    return {pose};
  }
};

TEST(FrameGraphExecutors, CollectPosesGathersEachNodesEstimatesOfTheFrame) {
  std::vector<std::unique_ptr<Node>> nodes;
  nodes.push_back(std::make_unique<PoseNode>());
  FrameGraph graph(std::move(nodes));
  SerialExecutor executor(graph);
  for (int index = 0; index < 4; ++index) {
    Frame frame;
    frame.index = index;
    frame.t_s = 0.5 * index;
    const FrameSlots slots = executor.Run(frame);
    const std::vector<PoseObservation> poses = graph.CollectPoses(slots);
    if (index % 2 == 1) {
      EXPECT_TRUE(poses.empty());
      continue;
    }
    ASSERT_EQ(poses.size(), 1u);
    EXPECT_EQ(poses[0].stream, "clock");
    EXPECT_EQ(poses[0].T_CX.translation().x(), frame.t_s);
    EXPECT_EQ(poses[0].t_s, frame.t_s);
  }
}

TEST(ParallelExecutor, RejectsNegativeConcurrency) {
  FrameGraph graph({});
  EXPECT_THROW(ParallelExecutor(graph, ParallelExecutorParams{-1}), std::invalid_argument);
}

TEST(TimingStats, PercentilesOfKnownSamples) {
  std::vector<double> durations(100);
  std::iota(durations.begin(), durations.end(), 1.0);  // 1 .. 100
  std::shuffle(durations.begin(), durations.end(), std::mt19937(3));
  const TimingStats stats = SummarizeDurations(durations);
  EXPECT_EQ(stats.count, 100);
  // Linear interpolation at position q * (n - 1): median between 50 and 51, p95 at 1 + 94.05.
  EXPECT_DOUBLE_EQ(stats.median_s, 50.5);
  EXPECT_DOUBLE_EQ(stats.p95_s, 95.05);
  EXPECT_DOUBLE_EQ(stats.max_s, 100.0);

  const TimingStats single = SummarizeDurations({0.25});
  EXPECT_EQ(single.count, 1);
  EXPECT_EQ(single.median_s, 0.25);
  EXPECT_EQ(single.p95_s, 0.25);

  EXPECT_EQ(SummarizeDurations({}).count, 0);
  EXPECT_EQ(SummarizeDurations({}).max_s, 0.0);
}

TEST(DurationRecord, ExactForShortRunsBoundedAndEvenlySpreadForLongOnes) {
  std::vector<double> durations(1000);
  std::iota(durations.begin(), durations.end(), 1.0);
  std::shuffle(durations.begin(), durations.end(), std::mt19937(5));
  DurationRecord short_run;
  for (double d : durations) short_run.Add(d);
  const TimingStats exact = SummarizeDurations(durations);
  EXPECT_EQ(short_run.Summary().count, exact.count);
  EXPECT_EQ(short_run.Summary().median_s, exact.median_s);
  EXPECT_EQ(short_run.Summary().p95_s, exact.p95_s);
  EXPECT_EQ(short_run.Summary().max_s, exact.max_s);

  // A ramp 0, 1, ..., n - 1 over ~10 x kMaxKept frames (an hour of 40 Hz frames is 144000): the
  // memory stays below kMaxKept durations, count and max stay exact, and the kept ones, evenly
  // spread over the run, give the ramp's median and p95 within 0.1 %.
  const int n = 10 * static_cast<int>(DurationRecord::kMaxKept) + 123;
  DurationRecord long_run;
  std::size_t most_kept = 0;
  for (int i = 0; i < n; ++i) {
    long_run.Add(i);
    most_kept = std::max(most_kept, long_run.kept());
  }
  EXPECT_LT(most_kept, DurationRecord::kMaxKept);
  const TimingStats stats = long_run.Summary();
  EXPECT_EQ(stats.count, n);
  EXPECT_EQ(stats.max_s, n - 1.0);
  EXPECT_NEAR(stats.median_s, 0.5 * (n - 1), 1e-3 * n);
  EXPECT_NEAR(stats.p95_s, 0.95 * (n - 1), 1e-3 * n);
}

}  // namespace
}  // namespace aperture::perception
