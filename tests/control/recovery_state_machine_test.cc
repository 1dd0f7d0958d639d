#include "control/recovery_state_machine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/constants.h"

namespace aperture::control {
namespace {

constexpr double kStateMachineDt_s = 0.002;

Eigen::Quaterniond Tilted(double angle_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d(1, 1, 0).normalized()));
}

HeightEstimate Height(double z, double z_dot, double time_since_init = 1.0) {
  return HeightEstimate{z, z_dot, time_since_init};
}

QuadState Vision(const Eigen::Vector3d& p, const Eigen::Vector3d& v) {
  QuadState s;
  s.p_WB = p;
  s.v_W = v;
  return s;
}

// Scripted driver: each Step() gets the next time stamp.
class Script {
 public:
  explicit Script(const RecoveryParams& params = {}) : machine_(vehicle_, params) {}
  RecoveryOutput Step(RecoveryInputs in) {
    in.t_s = (++step_) * kStateMachineDt_s;
    return machine_.Step(in);
  }
  RecoveryStateMachine& machine() { return machine_; }
  const VehicleParameters& vehicle() const { return vehicle_; }

 private:
  VehicleParameters vehicle_;
  RecoveryStateMachine machine_;
  int step_ = 0;
};

TEST(RecoveryStateMachine, StageNames) {
  EXPECT_STREQ(ToString(RecoveryStage::kWaitingForLaunch), "waiting_for_launch");
  EXPECT_STREQ(ToString(RecoveryStage::kAttitude), "attitude");
  EXPECT_STREQ(ToString(RecoveryStage::kVerticalVelocity), "vertical_velocity");
  EXPECT_STREQ(ToString(RecoveryStage::kHeight), "height");
  EXPECT_STREQ(ToString(RecoveryStage::kHorizontalVelocity), "horizontal_velocity");
  EXPECT_STREQ(ToString(RecoveryStage::kPosition), "position");
}

TEST(RecoveryStateMachine, WaitsForLaunchWithIdleRotors) {
  Script script;
  RecoveryInputs in;
  in.q_WB = Tilted(kPi);  // upside-down in the hand: still nothing happens before the launch
  for (int k = 0; k < 10; ++k) {
    const RecoveryOutput out = script.Step(in);
    EXPECT_EQ(out.stage, RecoveryStage::kWaitingForLaunch);
    EXPECT_EQ(out.command.collective_thrust_mps2, 0.0);
    EXPECT_TRUE(out.command.omega_des_B.isZero());
  }
  in.launch_detected = true;
  EXPECT_EQ(script.Step(in).stage, RecoveryStage::kWaitingForLaunch);  // command, then transition
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kAttitude);
}

TEST(RecoveryStateMachine, AttitudeStageLevelsWithThrustGAndExitsOnTiltAndRates) {
  Script script;
  RecoveryInputs in;
  in.launch_detected = true;
  script.Step(in);
  ASSERT_EQ(script.machine().stage(), RecoveryStage::kAttitude);
  const double g = script.vehicle().gravity_mps2;

  // Upside-down and tumbling: c = g, and the commanded rates reduce the tilt.
  in.q_WB = Tilted(0.9 * kPi);
  in.omega_B = Eigen::Vector3d(15.0, -3.0, 2.0);
  RecoveryOutput out = script.Step(in);
  EXPECT_EQ(out.stage, RecoveryStage::kAttitude);
  EXPECT_DOUBLE_EQ(out.command.collective_thrust_mps2, g);
  const Eigen::Quaterniond q_next =
      in.q_WB * Eigen::Quaterniond(Eigen::AngleAxisd(out.command.omega_des_B.norm() * 0.01,
                                                     out.command.omega_des_B.normalized()));
  EXPECT_GT((q_next * Eigen::Vector3d::UnitZ()).z(), (in.q_WB * Eigen::Vector3d::UnitZ()).z());

  // Tilt 21 deg (> 20) with small rates: stays. Tilt 19 deg with |omega_xy| = 10.5: stays.
  in.q_WB = Tilted(21.0 * kPi / 180.0);
  in.omega_B = Eigen::Vector3d(1.0, 1.0, 0.0);
  EXPECT_FALSE(script.Step(in).initialize_height_filter);
  in.q_WB = Tilted(19.0 * kPi / 180.0);
  in.omega_B = Eigen::Vector3d(10.5, 0.0, 0.0);
  EXPECT_FALSE(script.Step(in).initialize_height_filter);
  // The yaw rate does not count (only roll/pitch rates, B.3.2).
  in.omega_B = Eigen::Vector3d(6.0, -7.0, 25.0);  // |omega_xy| = 9.2
  out = script.Step(in);
  EXPECT_EQ(out.stage, RecoveryStage::kAttitude);
  EXPECT_TRUE(out.initialize_height_filter);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kVerticalVelocity);
  ASSERT_EQ(script.machine().transitions().size(), 2u);
}

// Drives the machine into `stage` with inputs that satisfy each exit condition in turn.
void DriveTo(Script& script, RecoveryStage stage) {
  RecoveryInputs in;
  in.launch_detected = true;
  in.height = Height(1.0, 0.0);
  in.vision_state = Vision(Eigen::Vector3d(0.3, -0.2, 1.1), Eigen::Vector3d::Zero());
  while (script.machine().stage() != stage) script.Step(in);
}

TEST(RecoveryStateMachine, VerticalVelocityStageControlsOnlyTheVerticalVelocity) {
  Script script;
  DriveTo(script, RecoveryStage::kVerticalVelocity);
  const double g = script.vehicle().gravity_mps2;
  const PositionControllerParams gains;
  RecoveryInputs in;
  // Filter not initialized yet: the stage-1 command (c = g, level) and no transition.
  RecoveryOutput out = script.Step(in);
  EXPECT_EQ(out.stage, RecoveryStage::kVerticalVelocity);
  EXPECT_DOUBLE_EQ(out.command.collective_thrust_mps2, g);
  // Falling at 1 m/s: c = g + d_z * 1 (level attitude); the height itself has no gain (P_pos = 0).
  in.height = Height(2.0, -1.0);
  out = script.Step(in);
  EXPECT_NEAR(out.command.collective_thrust_mps2, g + gains.d_z_per_s, 1e-9);
  in.height = Height(0.5, -1.0);
  EXPECT_NEAR(script.Step(in).command.collective_thrust_mps2, g + gains.d_z_per_s, 1e-9);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kVerticalVelocity);
  // |z_dot| = 0.25 < 0.3 but the filter has run only 0.1 s (< min_height_filter_time_s): stays.
  in.height = Height(0.8, 0.25, 0.1);
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kVerticalVelocity);
  // |z_dot| = 0.31: stays; 0.29: advances and the current height becomes the reference.
  in.height = Height(0.8, -0.31);
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kVerticalVelocity);
  in.height = Height(0.85, -0.29);
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kHeight);
  EXPECT_DOUBLE_EQ(script.machine().reference_height_m(), 0.85);
}

TEST(RecoveryStateMachine, HeightStageHoldsReferenceUntilVisionIsInitialized) {
  Script script;
  DriveTo(script, RecoveryStage::kVerticalVelocity);
  RecoveryInputs in;
  in.height = Height(1.4, 0.0);
  script.Step(in);
  ASSERT_EQ(script.machine().stage(), RecoveryStage::kHeight);
  const double g = script.vehicle().gravity_mps2;
  const PositionControllerParams gains;
  // 0.1 m below the reference: c = g + p_z 0.1.
  in.height = Height(1.3, 0.0);
  EXPECT_NEAR(script.Step(in).command.collective_thrust_mps2, g + gains.p_z_per_s2 * 0.1, 1e-9);
  for (int k = 0; k < 100; ++k) script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kHeight);  // no vision, no advance
  in.vision_state = Vision(Eigen::Vector3d(4.0, 2.0, 1.5), Eigen::Vector3d(1.0, 0.5, 0.0));
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kHorizontalVelocity);
}

TEST(RecoveryStateMachine, HorizontalVelocityStageBrakesAndLocksPosition) {
  Script script;
  DriveTo(script, RecoveryStage::kHorizontalVelocity);
  const double g = script.vehicle().gravity_mps2;
  RecoveryInputs in;
  in.height = Height(1.0, 0.0);
  // Moving at +1 m/s in x: the thrust direction tilts towards -x (a_des_x = -d_xy), i.e. a
  // negative pitch rate from level; the horizontal position error has no gain (p_xy = 0).
  in.vision_state = Vision(Eigen::Vector3d(0.3, -0.2, 1.1), Eigen::Vector3d(1.0, 0.0, 0.0));
  const RecoveryOutput a = script.Step(in);
  in.vision_state->p_WB.x() += 5.0;
  const RecoveryOutput b = script.Step(in);
  EXPECT_EQ(a.stage, RecoveryStage::kHorizontalVelocity);
  EXPECT_LT(a.command.omega_des_B.y(), -1.0);
  EXPECT_TRUE(a.command.omega_des_B.isApprox(b.command.omega_des_B, 1e-12));
  EXPECT_NEAR(a.command.collective_thrust_mps2, g, 1e-9);  // level, at the reference height
  // |v_xy| = 0.21: stays; 0.19 (with vertical speed, which does not count): locks.
  in.vision_state->v_W = Eigen::Vector3d(0.15, 0.15, 0.0);
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kHorizontalVelocity);
  in.vision_state->v_W = Eigen::Vector3d(0.19, 0.0, 0.5);
  in.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kPosition);
  EXPECT_TRUE(script.machine().locked_position_W().isApprox(in.vision_state->p_WB));
  EXPECT_NEAR(script.machine().locked_heading_rad(), 0.7, 1e-12);
  // Position stage: a horizontal position error now commands a tilt back to the lock.
  in.vision_state = Vision(script.machine().locked_position_W() + Eigen::Vector3d(1.0, 0, 0),
                           Eigen::Vector3d::Zero());
  const RecoveryOutput c = script.Step(in);
  EXPECT_EQ(c.stage, RecoveryStage::kPosition);
  EXPECT_GT(c.command.omega_des_B.norm(), 1.0);
  // Losing vision now is an error: recovery must restart.
  in.vision_state.reset();
  EXPECT_THROW(script.Step(in), std::invalid_argument);
  script.machine().Reset();
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kWaitingForLaunch);
  EXPECT_TRUE(script.machine().transitions().empty());
}

TEST(RecoveryStateMachine, SatisfiedStagesLastOneStepAndNoneIsSkipped) {
  // All exit conditions hold from the start (level, still, height settled, vision ready): the
  // thesis' "skipped" stages each last exactly one step, in order 0 -> 1 -> 2 -> 3 -> 4 -> 5.
  Script script;
  RecoveryInputs in;
  in.launch_detected = true;
  in.height = Height(1.0, 0.0);
  in.vision_state = Vision(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d::Zero());
  for (int k = 0; k < 5; ++k) {
    const RecoveryOutput out = script.Step(in);
    EXPECT_EQ(static_cast<int>(out.stage), k);
    EXPECT_EQ(out.initialize_height_filter, k == 1);
  }
  const auto& transitions = script.machine().transitions();
  ASSERT_EQ(transitions.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(static_cast<int>(transitions[k].from), k);
    EXPECT_EQ(static_cast<int>(transitions[k].to), k + 1);
    EXPECT_NEAR(transitions[k].t_s, (k + 1) * kStateMachineDt_s, 1e-12);
  }
  script.Step(in);
  EXPECT_EQ(script.machine().stage(), RecoveryStage::kPosition);  // terminal
}

TEST(RecoveryStateMachine, RejectsBadParamsAndInputs) {
  RecoveryParams params;
  params.max_vertical_speed_mps = -0.3;
  EXPECT_THROW(RecoveryStateMachine(VehicleParameters(), params), std::invalid_argument);
  RecoveryStateMachine machine{VehicleParameters()};
  RecoveryInputs in;
  in.omega_B.x() = NAN;
  EXPECT_THROW(machine.Step(in), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
