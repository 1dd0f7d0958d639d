// Closed loop: the moment servo flies the simulated quadrotor (sim/ dynamics with rotor drag and
// motor lag, the flight controller's LQR rate loop and mixer, a noisy gyro) from a displaced
// hover to the stand-off in front of a GapFlyt-like opening. The camera is modelled by
// projecting the opening's corners with the ground-truth pose at 30 Hz (no rendering: this
// checks the servo loop, not perception), de-rotated to the level view with the true attitude.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/position_controller.h"
#include "control/trajectory_point.h"
#include "free_camera_simulation.h"
#include "perception/autopilot.h"
#include "servo/level_view.h"
#include "servo/moment_servo.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::servo {
namespace {

constexpr double kCameraRate_hz = 30.0;  // the gapflyt scenario's front camera

// The `polygon` opening of the gapflyt scenario: 1.0 x 0.8 m in the wall x_W = 2.6 m (its
// foreground_x_m), centred at y = 0, z = 1.5 m; an irregular hexagon inside that box.
std::vector<Eigen::Vector3d> OpeningCorners_W() {
  const std::vector<Eigen::Vector2d> yz = {{0.5, 0.1},   {0.2, 0.4},   {-0.35, 0.3},
                                           {-0.5, -0.1}, {-0.1, -0.4}, {0.4, -0.3}};
  std::vector<Eigen::Vector3d> corners;
  for (const Eigen::Vector2d& c : yz) corners.emplace_back(2.6, c.x(), 1.5 + c.y());
  return corners;
}

std::vector<Eigen::Vector2d> Project(const Eigen::Isometry3d& T_WC,
                                     const std::vector<Eigen::Vector3d>& points_W) {
  std::vector<Eigen::Vector2d> image;
  for (const Eigen::Vector3d& p_W : points_W) {
    const Eigen::Vector3d p_C = T_WC.inverse() * p_W;
    image.emplace_back(p_C.x() / p_C.z(), p_C.y() / p_C.z());
  }
  return image;
}

// SIMULATION-ONLY test autopilot: servo step per camera frame, velocity reference to the
// position controller (no position feedback: p_ref = p) at the control rate.
class MomentServoAutopilot : public perception::Autopilot {
 public:
  MomentServoAutopilot(const control::VehicleParameters& vehicle, const Eigen::Isometry3d& T_BC,
                       const std::vector<Eigen::Vector2d>& desired_view, double desired_depth_m)
      : T_BC_(T_BC), servo_(MomentServoParams{}, T_BC), controller_(vehicle) {
    servo_.SetDesired(desired_view, desired_depth_m);
  }
  std::string name() const override { return "moment_servo_test"; }
  bool UsesGroundTruth() const override { return true; }
  void OnGroundTruth(const control::QuadState& state) override {
    state_ = state;
    have_state_ = true;
  }

  perception::AutopilotCommand Step(double t_s) override {
    perception::AutopilotCommand command;
    if (!have_state_) return command;
    const Eigen::Matrix3d R_WB = state_.q_WB.toRotationMatrix();
    const double heading = std::atan2(R_WB(1, 0), R_WB(0, 0));
    if (t_s >= next_frame_t_s_) {
      next_frame_t_s_ += 1.0 / kCameraRate_hz;
      Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
      T_WB.linear() = R_WB;
      T_WB.translation() = state_.p_WB;
      const auto level = LevelView(Project(T_WB * T_BC_, OpeningCorners_W()), R_WB, T_BC_.linear());
      if (level) {
        const ServoStepResult step = servo_.Step(*level);
        if (step.status == ServoStatus::kOk) reference_ = step.reference;
        error_norms_.push_back(step.error_norm);
      }
    }
    control::TrajectoryPoint reference;
    reference.t_s = t_s;
    reference.p_W = state_.p_WB;
    reference.v_W = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) * reference_.v_B;
    reference.heading_rad = heading;
    reference.heading_rate_radps = reference_.yaw_rate_radps;
    command.kind = perception::AutopilotCommand::Kind::kThrustRates;
    command.thrust_rates = controller_.Compute(state_, reference).command;
    return command;
  }

  const std::vector<double>& error_norms() const { return error_norms_; }

 private:
  Eigen::Isometry3d T_BC_;
  MomentServo servo_;
  control::PositionController controller_;
  control::QuadState state_;
  bool have_state_ = false;
  double next_frame_t_s_ = 0.0;
  BodyVelocityReference reference_;
  std::vector<double> error_norms_;
};

TEST(MomentServoSitlTest, ServoedQuadrotorReachesTheStandOffBeforeTheOpening) {
  const Eigen::Isometry3d T_BC = testing::ForwardCameraMount();
  // Goal: camera 1.2 m before the wall, on the opening's centre line.
  const Eigen::Isometry3d T_WB_goal = testing::LevelPose({2.6 - 1.2 - 0.1, 0.0, 1.5}, 0.0);
  sim::SitlRunnerParams params;
  params.duration_s = 8.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.4, 1.2);  // 1.3 m back, 0.4 m left, low
  params.SetSeed(5);                                           // default IMU noise and biases
  sim::SitlRunner runner(params, nullptr);
  MomentServoAutopilot autopilot(params.dynamics.vehicle, T_BC,
                                 Project(T_WB_goal * T_BC, OpeningCorners_W()), 1.2);
  const sim::SitlResult result = runner.Run(autopilot);
  ASSERT_EQ(result.outcome, sim::SitlResult::Outcome::kDurationReached) << result.reason;

  const std::vector<double>& errors = autopilot.error_norms();
  ASSERT_GT(errors.size(), 200u);  // 30 Hz over 8 s
  // 8 s at >= 0.7 /s leave < 0.4 % of the initial error on the model; the vehicle's velocity
  // loop lags the reference, so allow 2 %.
  EXPECT_LT(errors.back(), 0.02 * errors.front());
  const control::QuadState& end = result.trajectory.back();
  EXPECT_LT((end.p_WB - T_WB_goal.translation()).norm(), 0.03);
  EXPECT_LT(end.v_W.norm(), 0.05);
  // The vehicle never passed the stand-off towards the wall by more than 5 cm.
  for (const control::QuadState& state : result.trajectory) {
    ASSERT_LT(state.p_WB.x(), T_WB_goal.translation().x() + 0.05) << "t = " << state.t_s;
  }
}

}  // namespace
}  // namespace aperture::servo
