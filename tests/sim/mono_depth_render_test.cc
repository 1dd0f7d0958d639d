// Monocular depth against rendered ground truth (seed 003 Sec. III-A, Table I): a model trained
// on forest frames of some tree layouts predicts the depth of frames of another layout better
// than the best constant guess, and the model shipped in the repository does too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "perception/mono_depth/depth_errors.h"
#include "perception/mono_depth/mono_depth_estimator.h"
#include "perception/mono_depth/mono_depth_trainer.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/ground_truth_images.h"
#include "sim/scenario/kinematic_trajectory.h"
#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

struct DepthFrame {
  cv::Mat bgr;
  cv::Mat depth_mm;
};

// `count` colour frames of the forest with tree layout `seed`, flown as a lateral scan down the
// corridor (the views `aperture render forest --trajectory scan` gives), supersampling 1 for speed.
std::vector<DepthFrame> RenderForest(int seed, int count) {
  const config::ConfigTree tree = ScenarioConfig(
      "forest", {},
      {"seed=" + std::to_string(seed), "cameras.front.color=true", "cameras.front.supersampling=1",
       "trajectory.kind=scan", "trajectory.amplitude_m=0.8", "trajectory.end_p_m=[24, 0, 1.5]"});
  Scenario scenario = BuildScenario(LoadScenarioParams(tree));
  const ScenarioCamera& camera = scenario.render_camera();
  const KinematicTrajectory trajectory(scenario.params().trajectory, scenario.T_WB_start(), seed);
  RayCaster caster;
  std::vector<DepthFrame> frames;
  for (int i = 0; i < count; ++i) {
    const Eigen::Isometry3d T_WB = trajectory.T_WB((i + 0.5) / count);
    scenario.SetVehiclePose(T_WB);
    const CapturedFrame frame = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double) { return camera.T_WC(T_WB); },
        i / camera.rate_hz, i, camera.render);
    frames.push_back({frame.frame.image, DepthToMillimetres16U(frame.depth_C)});
  }
  return frames;
}

struct Scores {
  perception::DepthErrors model;
  perception::DepthErrors constant;  // the best single depth for these frames (median ln depth)
};

Scores Score(perception::MonoDepthEstimator& estimator, const std::vector<DepthFrame>& frames) {
  const perception::DepthLabels& labels = estimator.model().labels();
  std::vector<cv::Mat> truths, estimates;
  std::vector<float> ln_truth;
  for (const DepthFrame& frame : frames) {
    const perception::MonoDepthEstimate estimate = estimator.Estimate(frame.bgr);
    estimates.push_back(estimate.depth_m);
    truths.push_back(perception::PatchDepthFromMillimetres(frame.depth_mm, estimate.grid));
    for (auto it = truths.back().begin<float>(); it != truths.back().end<float>(); ++it) {
      if (std::isfinite(*it))
        ln_truth.push_back(
            std::log(std::clamp(*it, float(labels.MinDepth()), float(labels.MaxDepth()))));
    }
  }
  // The constant minimising mean |ln D - ln c| is the median of ln D: an oracle baseline that
  // even knows the held-out frames' depth distribution.
  std::nth_element(ln_truth.begin(), ln_truth.begin() + ln_truth.size() / 2, ln_truth.end());
  const float constant = std::exp(ln_truth[ln_truth.size() / 2]);
  Scores scores;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    scores.model +=
        perception::CompareDepth(estimates[i], truths[i], labels.MinDepth(), labels.MaxDepth());
    scores.constant +=
        perception::CompareDepth(cv::Mat(truths[i].size(), CV_32F, cv::Scalar(constant)), truths[i],
                                 labels.MinDepth(), labels.MaxDepth());
  }
  return scores;
}

TEST(MonoDepthRender, TrainedModelBeatsTheBestConstantOnAHeldOutLayout) {
  perception::MonoDepthTrainParams params;
  params.patch_stride = 3;  // every 3rd patch: neighbours are alike, and the test stays fast
  perception::MonoDepthTrainer trainer(params);
  for (int seed : {11, 12, 13}) {
    for (const DepthFrame& frame : RenderForest(seed, 5))
      trainer.AddFrame(frame.bgr, frame.depth_mm);
  }
  perception::MonoDepthTrainingReport report;
  perception::MonoDepthEstimator estimator(trainer.Train(&report));
  EXPECT_EQ(report.frames, 15u);
  EXPECT_EQ(report.patches, 15u * 40 * 30 / 3);
  const Scores held_out = Score(estimator, RenderForest(21, 4));
  ASSERT_GT(held_out.model.patches, 1000);
  // Depth from the cues must beat a constant that already knows the held-out depth distribution,
  // in both Table I errors, by a clear margin.
  EXPECT_LT(held_out.model.MeanLn(), 0.8 * held_out.constant.MeanLn())
      << "model E_ln " << held_out.model.MeanLn() << " constant " << held_out.constant.MeanLn();
  EXPECT_LT(held_out.model.MeanRelative(), held_out.constant.MeanRelative());
}

TEST(MonoDepthRender, ShippedModelBeatsTheBestConstantOnAHeldOutLayout) {
  perception::MonoDepthEstimator estimator(perception::DefaultMonoDepthModel());
  const Scores held_out = Score(estimator, RenderForest(977, 4));  // a seed no training used
  EXPECT_LT(held_out.model.MeanLn(), 0.8 * held_out.constant.MeanLn())
      << "model E_ln " << held_out.model.MeanLn() << " constant " << held_out.constant.MeanLn();
  EXPECT_LT(held_out.model.MeanRelative(), held_out.constant.MeanRelative());
}

}  // namespace
}  // namespace aperture::sim
