// The SITL's CPU profile (SitlTiming::cpu, sim/render/render_profile.h) and the frames an
// autopilot ignores (Autopilot::WantsFrame, SitlRunnerParams::render_ignored_frames).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/render/ray_caster.h"
#include "sim/render/render_profile.h"
#include "sim/scene/textures.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/sitl_runner.h"
#include "tests/support/quiet_sitl_params.h"
#include "tests/support/textured_box_scene.h"

namespace aperture::sim {
namespace {

using test_support::HoverAt;

// 160 x 120 pinhole looking forward along x_B at a textured box: edges to supersample.
SitlCamera ProfiledCamera() {
  SitlCamera camera;
  camera.name = "front";
  camera.model = std::make_shared<perception::PinholeCamera>(
      160, 120, perception::PinholeIntrinsics{80.0, 80.0, 79.5, 59.5});
  camera.rate_hz = 30.0;
  camera.T_BC.linear() = perception::OpticalAxesAlongX();
  camera.effects.full_well_electrons = 2000.0;
  camera.effects.read_noise_sigma = 0.01;
  camera.effects.exposure_s = 4e-3;
  camera.effects.motion_blur_subframes = 2;
  camera.render.supersampling = 2;
  camera.render.ground_truth = false;
  return camera;
}

using test_support::TexturedBoxScene;

// Hovers and records the frames it is given; wants none stamped after ignore_after_s.
class FrameCountingAutopilot : public GroundTruthAutopilot {
 public:
  FrameCountingAutopilot(const control::VehicleParameters& vehicle, const Eigen::Vector3d& p_W,
                         double ignore_after_s)
      : GroundTruthAutopilot(vehicle, HoverAt(p_W)), ignore_after_s_(ignore_after_s) {}
  void OnFrame(const perception::Frame& frame) override {
    if (WantsFrame(frame.camera_id, frame.t_s)) wanted_indices.push_back(frame.index);
  }
  bool WantsFrame(int /*camera_id*/, double t_s) const override { return t_s <= ignore_after_s_; }
  std::vector<int> wanted_indices;

 private:
  double ignore_after_s_;
};

TEST(SitlProfile, EveryStageIsPresentAndTheStagesSumToTheTotal) {
  const Scene scene = TexturedBoxScene();
  SitlRunnerParams params = test_support::QuietSitlParams(2.0);
  params.cameras.push_back(ProfiledCamera());
  SitlRunner runner(params, &scene);
  FrameCountingAutopilot autopilot(params.dynamics.vehicle, params.initial_state.p_WB, 1e9);
  // A hook that renders (as `aperture sim`'s chase view does) is the hooks' time, not the
  // camera's: its renders stay out of the render profile.
  RayCaster hook_caster;
  int hook_renders = 0;
  SitlHooks hooks;
  hooks.on_frame = [&](int, const CapturedFrame&, const control::QuadState&) {
    Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
    T_WC.linear() = params.cameras[0].T_BC.linear();
    T_WC.translation() = params.initial_state.p_WB;
    hook_caster.Render(scene, *params.cameras[0].model, T_WC);
    ++hook_renders;
  };
  const SitlResult result = runner.Run(autopilot, hooks);
  const SitlCpuProfile& cpu = result.timing.cpu;
  const RenderProfile& render = cpu.render;
  ASSERT_EQ(result.cameras.size(), 1u);
  const int frames = result.cameras[0].frames_delivered;
  EXPECT_EQ(frames, 61);  // 30 Hz over [0, 2] s
  EXPECT_EQ(hook_renders, frames);
  EXPECT_EQ(render.renders, 2 * frames);  // two motion-blur subframes each, the hook's not counted
  for (const double stage_s :
       {cpu.dynamics_s, cpu.render_s, cpu.control_s, cpu.collision_s, cpu.hooks_s, render.setup_s,
        render.centers_s, render.supersampling_s, render.blur_s, render.noise_s}) {
    EXPECT_GT(stage_s, 0.0);
  }
  EXPECT_GE(cpu.perception_s, 0.0);  // OnFrame only stores an index here
  EXPECT_GE(render.leds_s, 0.0);     // no LED in the scene
  // The stages are disjoint parts of the run: they sum to at most the total, and the time
  // outside them (the loop itself, oneTBB's workers finishing) is a small part of it.
  EXPECT_LE(render.total_s(), cpu.render_s * 1.001 + 1e-4);
  EXPECT_LE(cpu.stages_s(), cpu.total_s * 1.001 + 1e-4);
  EXPECT_GE(cpu.stages_s(), 0.5 * cpu.total_s);
}

// Frames the autopilot would ignore are neither rendered nor delivered, and nothing else changes:
// the same drops (drawn first), the same frames before, the same flight.
TEST(SitlProfile, IgnoredFramesAreSkippedAndTheFlightIsTheSame) {
  const Scene scene = TexturedBoxScene();
  SitlRunnerParams params = test_support::QuietSitlParams(1.0);
  SitlCamera camera = ProfiledCamera();
  camera.model = std::make_shared<perception::PinholeCamera>(
      40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});
  camera.drop_probability = 0.3;
  params.cameras.push_back(camera);
  params.imu.accel_noise_density = 0.02;  // noise, so that a changed stream would show
  params.SetSeed(5);
  struct Run {
    SitlResult result;
    std::vector<int> wanted;
  };
  const auto fly = [&](bool render_ignored_frames) {
    SitlRunnerParams p = params;
    p.render_ignored_frames = render_ignored_frames;
    SitlRunner runner(p, &scene);
    FrameCountingAutopilot autopilot(p.dynamics.vehicle, p.initial_state.p_WB, 0.5);
    Run run{runner.Run(autopilot), {}};
    run.wanted = autopilot.wanted_indices;
    return run;
  };
  const Run all = fly(true);
  const Run skipping = fly(false);
  const SitlCameraStats& a = all.result.cameras.at(0);
  const SitlCameraStats& s = skipping.result.cameras.at(0);
  EXPECT_EQ(a.frames_skipped, 0);
  EXPECT_GT(s.frames_skipped, 5);
  EXPECT_EQ(s.frames_due, a.frames_due);
  EXPECT_EQ(s.frames_dropped, a.frames_dropped);
  EXPECT_EQ(s.frames_delivered + s.frames_skipped, a.frames_delivered);
  EXPECT_EQ(skipping.result.timing.cpu.render.renders + 2 * s.frames_skipped,
            all.result.timing.cpu.render.renders);
  EXPECT_EQ(skipping.wanted, all.wanted);
  ASSERT_EQ(skipping.result.trajectory.size(), all.result.trajectory.size());
  for (size_t i = 0; i < all.result.trajectory.size(); ++i) {
    ASSERT_EQ(skipping.result.trajectory[i].p_WB, all.result.trajectory[i].p_WB) << "step " << i;
  }
}

}  // namespace
}  // namespace aperture::sim
