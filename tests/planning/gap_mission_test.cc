// GapMission's phase logic without the simulator: a static vehicle hovering 4 m in front of a
// gap drawn through an exact pinhole projection (tests/perception/gap_test_images.h), an ideal
// IMU at rest, frames at 30 Hz and control steps at 100 Hz. The closed-loop flight through the
// rendered gap is tests/experiments/gap_mission_sitl_test.cc.
#include "planning/gap_mission/gap_mission.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "config/config_tree.h"
#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "planning/gap_mission/gap_mission_params_io.h"
#include "planning/primitive_feasibility.h"
#include "tests/perception/gap_test_images.h"
#include "tests/support/pinhole_752x480.h"

namespace aperture::planning {
namespace {

constexpr double kGravity = 9.81;
constexpr double kRollRad = 30.0 * M_PI / 180.0;

// Forward camera 10 cm ahead of the centre of mass: z_C = x_B, x_C = -y_B, y_C = -z_B.
Eigen::Isometry3d ForwardCameraMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = perception::OpticalAxesAlongX();
  T_BC.translation() = Eigen::Vector3d(0.1, 0.0, 0.0);
  return T_BC;
}

// The gap 4 m ahead of the level vehicle at (0, 0, 1.5), facing it (z_G = x_W), rolled by 30 deg
// about x_W; x_G points to the image's right (-y_W), the detector's convention.
Eigen::Isometry3d TrueGap() {
  const Eigen::Matrix3d R_facing = perception::OpticalAxesAlongX();
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  T_WG.linear() =
      Eigen::AngleAxisd(kRollRad, Eigen::Vector3d::UnitX()).toRotationMatrix() * R_facing;
  T_WG.translation() = Eigen::Vector3d(4.0, 0.0, 1.5);
  return T_WG;
}

class GapMissionTest : public ::testing::Test {
 protected:
  explicit GapMissionTest(const GapMissionParams& params = GapMissionParams{})
      : mission_(params, test_support::Pinhole752x480(), ForwardCameraMount(),
                 control::VehicleParameters{}) {
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.translation() = p_WB_;
    const Eigen::Isometry3d T_CG = (T_WB * ForwardCameraMount()).inverse() * TrueGap();
    gap_image_ = perception::DrawGapPattern(*test_support::Pinhole752x480(),
                                            perception::GapDetectorParams{}, T_CG);
    blank_image_ = cv::Mat(480, 752, CV_8UC1, cv::Scalar(90));
  }

  // Runs the sensors and the control loop in 1 ms steps from the current time until `until_s` or
  // `stop` holds after a control step; frames show the gap while `gap_visible`.
  template <typename Stop>
  void Run(double until_s, bool gap_visible, Stop stop) {
    for (; step_ * 1e-3 <= until_s; ++step_) {
      const double t = step_ * 1e-3;
      if (step_ % 2 == 0) {  // 500 Hz IMU at rest: specific force = gravity, up in B
        mission_.OnImu({t, Eigen::Vector3d(0.0, 0.0, kGravity), Eigen::Vector3d::Zero()});
      }
      if (step_ % 33 == 0) {  // ~30 Hz camera
        perception::Frame frame;
        frame.t_s = t;
        frame.index = frame_index_++;
        frame.image = gap_visible ? gap_image_ : blank_image_;
        mission_.OnFrame(frame);
      }
      if (step_ % 20 == 0 && odometry_) mission_.OnOdometry(odometry_(t));    // 50 Hz
      if (step_ % 10 == 0 && range_) mission_.OnRange({t, range_(t), true});  // 100 Hz
      if (step_ % 10 == 0) {
        last_command_ = mission_.Step(t);
        if (stop()) {
          ++step_;
          return;
        }
      }
    }
  }

  const Eigen::Vector3d p_WB_{0.0, 0.0, 1.5};
  GapMission mission_;
  cv::Mat gap_image_, blank_image_;
  perception::AutopilotCommand last_command_;
  // The body pose the visual odometry reports at t (none when empty).
  std::function<perception::PoseMeasurement(double t)> odometry_;
  // The downward range sensor's reading at t [m] (none when empty).
  std::function<double(double t)> range_;
  int step_ = 0;
  int frame_index_ = 0;
};

TEST_F(GapMissionTest, HoversOpenLoopUntilTheGapIsSeen) {
  const perception::AutopilotCommand command = mission_.Step(0.0);
  EXPECT_EQ(command.kind, perception::AutopilotCommand::Kind::kThrustRates);
  EXPECT_DOUBLE_EQ(command.thrust_rates.collective_thrust_mps2, kGravity);
  EXPECT_TRUE(command.thrust_rates.omega_des_B.isZero());
  EXPECT_FALSE(mission_.has_estimate());
  EXPECT_TRUE(std::isnan(mission_.traverse_start_time_s()));
  // No gap in 1 s of frames: still detecting, never done.
  Run(1.0, false, [] { return false; });
  EXPECT_EQ(mission_.phase(), GapMissionPhase::kDetect);
  EXPECT_EQ(mission_.detections(), 0);
  EXPECT_FALSE(last_command_.done);
}

TEST_F(GapMissionTest, DetectHoldsTheAttitudeOfTheStart) {
  // A weak rotor rolls the vehicle at 0.5 rad/s for 0.1 s before the gap is seen: the detect
  // phase steers back to the attitude of the first IMU sample (the attitude controller's
  // p_rp times the 0.05 rad roll) instead of holding zero rates, which would keep the tilt.
  const double roll_rate_radps = 0.5;
  for (int k = 0; k <= 50; ++k) {  // 500 Hz for 0.1 s
    mission_.OnImu({k * 2e-3, Eigen::Vector3d(0.0, 0.0, kGravity),
                    Eigen::Vector3d(roll_rate_radps, 0.0, 0.0)});
  }
  const perception::AutopilotCommand command = mission_.Step(0.1);
  const double p_rp = GapMissionParams{}.controller.attitude.p_rp_per_s;
  EXPECT_NEAR(command.thrust_rates.omega_des_B.x(), -p_rp * roll_rate_radps * 0.1,
              0.1 * p_rp * roll_rate_radps * 0.1);
  EXPECT_NEAR(command.thrust_rates.omega_des_B.y(), 0.0, 1e-9);
  EXPECT_EQ(mission_.phase(), GapMissionPhase::kDetect);
}

TEST_F(GapMissionTest, DetectsHoversAndPlansInTheGapAnchoredFrame) {
  Run(5.0, true, [&] {
    return mission_.phase() != GapMissionPhase::kDetect &&
           mission_.phase() != GapMissionPhase::kHover;
  });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kTransfer) << mission_.reason();
  const auto& changes = mission_.phase_changes();
  ASSERT_EQ(changes.size(), 3u);
  EXPECT_EQ(changes[1].phase, GapMissionPhase::kHover);
  EXPECT_EQ(changes[2].phase, GapMissionPhase::kTransfer);
  // The frame is fixed after init_detections (10) frames at 30 Hz: the 10th comes at 9 * 33 ms.
  EXPECT_GE(changes[1].t_s, 9 * 0.033);
  EXPECT_LT(changes[1].t_s, 11 * 0.033);
  EXPECT_GE(changes[2].t_s - changes[1].t_s, GapMissionParams{}.hover_s - 1e-9);

  // Mission frame: origin at the gap centre, z_W up, x_W the horizontal gap normal. The true
  // normal is x_W, so the mission frame is W shifted to the gap: the vehicle is at (-4, 0, 0)
  // and the gap's axes are the true ones. 2 cm (0.5 % of the distance, half the detector's
  // accuracy target of 1 %) and 0.3 deg bound the detector's error on drawn patterns (a fraction
  // of a pixel at 4 m) carried into the anchored frame, plus the filter's wander over 1.3 s.
  const control::QuadState x = mission_.estimate();
  EXPECT_LT((x.p_WB - (p_WB_ - TrueGap().translation())).norm(), 0.02) << x.p_WB.transpose();
  EXPECT_LT(x.v_W.norm(), 0.02);
  EXPECT_LT(Eigen::AngleAxisd(x.q_WB).angle(), 0.3 * M_PI / 180.0);
  EXPECT_TRUE(mission_.gap_W().p_WG.isZero());
  EXPECT_LT(Eigen::AngleAxisd(mission_.gap_W().R_WG.transpose() * TrueGap().linear()).angle(),
            0.3 * M_PI / 180.0);

  // The plan: traverse through the estimated gap, approach ending lead_in_s before its start on
  // its arc (3)-(5).
  ASSERT_TRUE(mission_.traverse_plan().has_value());
  ASSERT_TRUE(mission_.approach_plan().has_value());
  const TraverseTrajectory& traverse = *mission_.traverse_plan();
  EXPECT_TRUE(traverse.Position(traverse.time_to_gap_s()).isZero(1e-9));  // through the centre
  const MotionPrimitive& approach = mission_.approach_plan()->primitive;
  const double lead_in_s = GapMissionParams{}.lead_in_s;
  EXPECT_TRUE(
      approach.Position(approach.duration_s()).isApprox(traverse.Position(-lead_in_s), 1e-9));
  EXPECT_TRUE(
      approach.Velocity(approach.duration_s()).isApprox(traverse.Velocity(-lead_in_s), 1e-9));
  EXPECT_TRUE(
      approach.Acceleration(approach.duration_s()).isApprox(traverse.plane_gravity_W(), 1e-9));
  EXPECT_TRUE(std::isnan(mission_.traverse_start_time_s()));
  // Transfer starts at hover: the command's thrust is close to hover, the vehicle upright.
  EXPECT_NEAR(last_command_.thrust_rates.collective_thrust_mps2, kGravity, 1.0);
}

// Approach limits no candidate meets (as at steep gaps): the fallback limits plan the approach to
// the traverse start itself, without the lead-in, and the lead-in phase is skipped.
GapMissionParams UnreachableApproachLimitsParams() {
  GapMissionParams params;
  params.approach.limits.max_body_rate_radps = 0.05;
  return params;
}

class GapMissionFallbackTest : public GapMissionTest {
 protected:
  GapMissionFallbackTest() : GapMissionTest(UnreachableApproachLimitsParams()) {}
};

TEST_F(GapMissionFallbackTest, PlansTheFallbackApproachToTheTraverseStartWithoutALeadIn) {
  ASSERT_GT(GapMissionParams{}.lead_in_s, 0.0);
  Run(5.0, true, [&] {
    return mission_.phase() != GapMissionPhase::kDetect &&
           mission_.phase() != GapMissionPhase::kHover;
  });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kTransfer) << mission_.reason();
  EXPECT_TRUE(mission_.used_fallback_limits());
  ASSERT_TRUE(mission_.traverse_plan().has_value());
  ASSERT_TRUE(mission_.approach_plan().has_value());
  const TraverseTrajectory& traverse = *mission_.traverse_plan();
  const MotionPrimitive& approach = mission_.approach_plan()->primitive;
  const double T = approach.duration_s();
  EXPECT_TRUE(approach.Position(T).isApprox(traverse.start_position_W(), 1e-9));
  EXPECT_TRUE(approach.Velocity(T).isApprox(traverse.start_velocity_W(), 1e-9));
  // Flown on (the gap stays in view): the approach's end starts the open-loop traverse at once.
  Run(15.0, true, [&] { return mission_.phase() == GapMissionPhase::kTraverse; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kTraverse) << mission_.reason();
  const auto& changes = mission_.phase_changes();
  ASSERT_GE(changes.size(), 2u);
  EXPECT_EQ(changes[changes.size() - 2].phase, GapMissionPhase::kLeadIn);
  EXPECT_EQ(changes.back().t_s, changes[changes.size() - 2].t_s);  // a lead-in of no time
}

// With a range reading the approach and the transfer to its start stay min_ground_clearance_m
// above the ground measured while hovering. The range says 1 m, so the floor is 0.5 m below the
// hover (z_W = 0): without it the cheapest approach through the 30 deg gap dips 1.1 m below the
// gap centre, and a transfer that descended below its end points would fail too.
TEST_F(GapMissionTest, TransferAndApproachStayAboveTheFloor) {
  constexpr double kRangeM = 1.0;
  Run(5.0, true, [&] {
    mission_.OnRange({step_ * 1e-3, kRangeM, true});
    return mission_.phase() != GapMissionPhase::kDetect &&
           mission_.phase() != GapMissionPhase::kHover;
  });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kTransfer) << mission_.reason();
  const double floor_m =
      mission_.estimate().p_WB.z() - kRangeM + GapMissionParams{}.min_ground_clearance_m;
  const double transfer_min_m =
      MinimumProjection(mission_.transfer_plan(), Eigen::Vector3d::UnitZ());
  EXPECT_GE(transfer_min_m, floor_m);
  ASSERT_TRUE(mission_.approach_plan().has_value());
  EXPECT_GE(MinimumProjection(mission_.approach_plan()->primitive, Eigen::Vector3d::UnitZ()),
            floor_m);
  // The transfer ends where the approach starts.
  EXPECT_TRUE(mission_.transfer_plan()
                  .Position(mission_.transfer_plan().duration_s())
                  .isApprox(mission_.approach_plan()->primitive.initial_position_W(), 1e-9));
}

// The hover ends at the first control step after hover_s at which the filter's position sigma is
// within init_max_relative_sigma of the estimated distance to the gap (4 m here).
void ExpectHoverEndsWhenSigmaIsSmallRelativeToTheDistance(
    GapMission& mission, const std::function<void(double, std::function<bool()>)>& run,
    const GapMissionParams& params) {
  double last_hover_t_s = -1.0, last_hover_ratio = 0.0;
  run(10.0, [&] {
    if (mission.phase() == GapMissionPhase::kHover) {
      last_hover_t_s = mission.phase_changes().back().t_s;
      last_hover_ratio = mission.position_sigma_m() / mission.estimate().p_WB.norm();
    }
    return mission.phase() != GapMissionPhase::kDetect &&
           mission.phase() != GapMissionPhase::kHover;
  });
  ASSERT_EQ(mission.phase(), GapMissionPhase::kTransfer) << mission.reason();
  const auto& changes = mission.phase_changes();
  const double hover_start_s = changes[1].t_s, plan_s = changes[2].t_s;
  // Planning does not change the filter: its sigma now is the one the decision saw.
  const double ratio = mission.position_sigma_m() / mission.estimate().p_WB.norm();
  EXPECT_LE(ratio, params.init_max_relative_sigma);
  EXPECT_GE(plan_s - hover_start_s, params.hover_s - 1e-9);
  // The step before (10 ms earlier) was still hovering for want of hover_s or of a small sigma.
  if (plan_s - 0.01 - hover_start_s >= params.hover_s) {
    EXPECT_GT(last_hover_ratio, params.init_max_relative_sigma) << "at " << last_hover_t_s;
  }
}

TEST_F(GapMissionTest, PlansWhenThePositionIsKnownRelativeToTheDistance) {
  ExpectHoverEndsWhenSigmaIsSmallRelativeToTheDistance(
      mission_, [&](double until_s, std::function<bool()> stop) { Run(until_s, true, stop); },
      GapMissionParams{});
  // At 4 m the default 2 % (8 cm) is reached within a second of hover: the absolute 5 cm that
  // this replaced kept the vehicle hovering for ~8 s at 5 m.
  const auto& changes = mission_.phase_changes();
  EXPECT_LT(changes[2].t_s - changes[1].t_s, 1.0);
}

// 0.5 % = 2 cm at 4 m: the filter needs ~2.4 s of the drawn pattern's detections for it.
GapMissionParams StrictSigmaParams() {
  GapMissionParams params;
  params.init_max_relative_sigma = 0.005;
  return params;
}

class GapMissionStrictSigmaTest : public GapMissionTest {
 protected:
  GapMissionStrictSigmaTest() : GapMissionTest(StrictSigmaParams()) {}
};

// A tighter ratio waits longer for the same detections: the sigma, not hover_s, ends the hover.
TEST_F(GapMissionStrictSigmaTest, WaitsLongerForATighterRatio) {
  ExpectHoverEndsWhenSigmaIsSmallRelativeToTheDistance(
      mission_, [&](double until_s, std::function<bool()> stop) { Run(until_s, true, stop); },
      StrictSigmaParams());
  const auto& changes = mission_.phase_changes();
  EXPECT_GT(changes[2].t_s - changes[1].t_s, StrictSigmaParams().hover_s + 0.1);
}

TEST_F(GapMissionTest, AbortsIntoRecoveryWhenTheGapIsLost) {
  Run(5.0, true, [&] { return mission_.phase() == GapMissionPhase::kHover; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kHover);
  const double lost_s = step_ * 1e-3;
  Run(5.0, false, [&] { return mission_.phase() != GapMissionPhase::kHover; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kAborted);
  EXPECT_NE(mission_.reason().find("lost"), std::string::npos) << mission_.reason();
  // Aborted detection_timeout_s after the last detection (one frame period before lost_s at most).
  const double abort_s = mission_.phase_changes().back().t_s;
  EXPECT_GE(abort_s, lost_s - 0.034 + GapMissionParams{}.detection_timeout_s - 1e-9);
  EXPECT_LE(abort_s, lost_s + GapMissionParams{}.detection_timeout_s + 0.011);
  EXPECT_EQ(last_command_.kind, perception::AutopilotCommand::Kind::kThrustRates);
  EXPECT_NE(mission_.status().find("aborted"), std::string::npos);
  // The static vehicle is level and at rest, so the recovery reaches its position stage and, after
  // recovered_hold_s, reports done.
  Run(10.0, false, [&] { return last_command_.done; });
  EXPECT_TRUE(last_command_.done);
  EXPECT_EQ(mission_.phase(), GapMissionPhase::kAborted);
}

// The recovery's visual odometry: ignored until recovery_odometry_delay_s after the recovery
// starts, then aligned to the estimate over its first poses (rotation, position) and fused. Its
// frame O is turned by 90 deg against W and offset; it reports the body moving at 0.2 m/s along
// x_O, which the IMU (at rest here) does not see, so the fused estimate must take that velocity,
// turned into W.
// Visual odometry reporting the body moving at 0.2 m/s along x_O, with O turned by 90 deg about
// z against W (x_O = -y_W) and offset; 2 cm and 0.5 deg noise sigmas (no noise drawn).
perception::PoseMeasurement OdometryMovingAlongXo(double t_s) {
  const Eigen::Vector3d v_O(0.2, 0.0, 0.0);
  perception::PoseMeasurement z;
  z.t_s = t_s;
  z.p_WX = Eigen::Vector3d(2.0, 3.0, 0.5) + v_O * t_s;
  z.q_WX = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  z.covariance.setZero();
  z.covariance.diagonal() << 4e-4, 4e-4, 4e-4, 7.6e-5, 7.6e-5, 7.6e-5;
  return z;
}
const Eigen::Vector3d kOdometryVelocity_W(0.0, -0.2, 0.0);  // OdometryMovingAlongXo's, in W

TEST_F(GapMissionTest, FusesTheRecoveryOdometryOnlyAfterItHasInitialized) {
  odometry_ = OdometryMovingAlongXo;
  Run(5.0, true, [&] { return mission_.phase() == GapMissionPhase::kHover; });
  Run(5.0, false, [&] { return mission_.phase() == GapMissionPhase::kAborted; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kAborted);
  EXPECT_EQ(mission_.odometry_poses_fused(), 0);  // not before the recovery
  const double abort_s = mission_.phase_changes().back().t_s;
  const double delay_s = GapMissionParams{}.recovery_odometry_delay_s;
  Run(abort_s + delay_s - 0.01, false, [] { return false; });
  EXPECT_EQ(mission_.odometry_poses_fused(), 0);  // still initializing
  // The first recovery_odometry_alignment_poses (50 Hz) are averaged into the alignment, then
  // fused with every later one.
  const double alignment_s = GapMissionParams{}.recovery_odometry_alignment_poses / 50.0;
  Run(abort_s + delay_s + alignment_s - 0.03, false, [] { return false; });
  EXPECT_EQ(mission_.odometry_poses_fused(), 0);  // still aligning
  const Eigen::Vector3d p_before = mission_.estimate().p_WB;
  Run(abort_s + delay_s + alignment_s + 0.05, false, [] { return false; });
  EXPECT_GE(mission_.odometry_poses_fused(), GapMissionParams{}.recovery_odometry_alignment_poses);
  // Aligned to the estimate: no jump. In these 80 ms the body moves 1.6 cm, and the mean of a
  // run moving at 0.2 m/s sits mid-run, ~2 cm from its last pose.
  EXPECT_LT((mission_.estimate().p_WB - p_before).norm(), 0.05);
  Run(abort_s + delay_s + 3.0, false, [] { return false; });
  // x_O is -y_W (O's heading of the body is 90 deg, W's 0).
  EXPECT_LT((mission_.estimate().v_W - kOdometryVelocity_W).norm(), 0.05)
      << mission_.estimate().v_W.transpose();
}

// A filter that starts sure of its velocity (1 cm/s), attitude and accelerometer bias, and so is
// still sure of its velocity after the IMU-only recovery, as in SITL after a traverse (velocity
// sigma ~1 cm/s there; the short hover of this fixture would not converge the attitude).
GapMissionParams ConfidentVelocityParams() {
  GapMissionParams params;
  params.filter.initial_velocity_sigma_mps = 0.01;
  params.filter.initial_attitude_sigma_rad = 0.002;
  params.filter.initial_accel_bias_sigma_mps2 = 0.005;
  return params;
}

class GapMissionConfidentVelocityTest : public GapMissionTest {
 protected:
  GapMissionConfidentVelocityTest() : GapMissionTest(ConfidentVelocityParams()) {}
};

// The IMU-only recovery leaves a velocity the filter is overconfident in (here 0.2 m/s off, the
// IMU at rest while the odometry moves). Aligning the odometry widens the velocity's sigma, so its
// poses correct the velocity within 0.3 s, without the gate rejecting them into a restart (whose
// position jump the hold turns into a jolt).
TEST_F(GapMissionConfidentVelocityTest, TheAlignedOdometryCorrectsTheVelocityWithoutARestart) {
  odometry_ = OdometryMovingAlongXo;
  Run(5.0, true, [&] { return mission_.phase() == GapMissionPhase::kHover; });
  Run(5.0, false, [&] { return mission_.phase() == GapMissionPhase::kAborted; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kAborted);
  const double abort_s = mission_.phase_changes().back().t_s;
  const GapMissionParams defaults;
  const double aligned_s = abort_s + defaults.recovery_odometry_delay_s +
                           defaults.recovery_odometry_alignment_poses / 50.0;
  Run(aligned_s + 0.3, false, [] { return false; });
  EXPECT_LT((mission_.estimate().v_W - kOdometryVelocity_W).norm(), 0.05)
      << mission_.estimate().v_W.transpose();
  Run(aligned_s + 3.0, false, [] { return false; });
  EXPECT_EQ(mission_.filter_restarts(), 0);
  EXPECT_LT((mission_.estimate().v_W - kOdometryVelocity_W).norm(), 0.02)
      << mission_.estimate().v_W.transpose();
}

// Done only after recovered_hold_s on the vision-based estimate: the hold in the position stage
// counts anew from the odometry's first pose (the static vehicle reaches the position stage well
// before the odometry has initialized).
TEST_F(GapMissionTest, DoneOnlyAfterHoldingOnTheRecoveryOdometry) {
  odometry_ = [](double t) {
    perception::PoseMeasurement z;
    z.t_s = t;
    z.p_WX = Eigen::Vector3d(1.0, 2.0, 3.0);
    z.covariance = perception::Matrix6d::Identity() * 1e-4;
    return z;
  };
  Run(5.0, true, [&] { return mission_.phase() == GapMissionPhase::kHover; });
  Run(5.0, false, [&] { return mission_.phase() == GapMissionPhase::kAborted; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kAborted);
  const double abort_s = mission_.phase_changes().back().t_s;
  Run(15.0, false, [&] { return last_command_.done; });
  ASSERT_TRUE(last_command_.done);
  const GapMissionParams defaults;
  EXPECT_GE(step_ * 1e-3,
            abort_s + defaults.recovery_odometry_delay_s + defaults.recovered_hold_s - 0.011);
  EXPECT_GT(mission_.odometry_poses_fused(), 0);
}

// The range sensor in the recovery: after the abort the range shrinks at 5 cm/s (the vehicle
// sinks, the IMU at rest does not see it). Its readings, heights above the floor fixed while
// hovering, carry the estimate down with it; before the recovery they are not fused.
GapMissionParams RangeInTheRecoveryParams() {
  GapMissionParams params;
  params.recovery_range_sigma_m = 0.02;
  return params;
}

class GapMissionRangeTest : public GapMissionTest {
 protected:
  GapMissionRangeTest() : GapMissionTest(RangeInTheRecoveryParams()) {}
};

TEST_F(GapMissionRangeTest, TheRecoveryFusesTheRangeAsHeightAboveTheFloor) {
  const double hover_range_m = 1.5;
  double sink_from_s = std::numeric_limits<double>::infinity();
  range_ = [&](double t) { return hover_range_m - 0.05 * std::max(0.0, t - sink_from_s); };
  Run(5.0, true, [&] { return mission_.phase() == GapMissionPhase::kHover; });
  Run(5.0, false, [&] { return mission_.phase() == GapMissionPhase::kAborted; });
  ASSERT_EQ(mission_.phase(), GapMissionPhase::kAborted);
  const double z_at_abort_m = mission_.estimate().p_WB.z();
  sink_from_s = mission_.phase_changes().back().t_s + 0.2;
  Run(sink_from_s + 2.0, false, [] { return false; });
  // 10 cm down in 2 s.
  EXPECT_NEAR(mission_.estimate().p_WB.z(), z_at_abort_m - 0.1, 0.02);
  EXPECT_NEAR(mission_.estimate().v_W.z(), -0.05, 0.03);
}

TEST(GapMissionParamsTest, RejectsInvalidValuesAndInputs) {
  GapMissionParams params;
  params.init_detections = 0;
  try {
    params.Validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("init_detections"), std::string::npos) << e.what();
  }
  params = GapMissionParams{};
  params.detection_timeout_s = 0.0;
  EXPECT_THROW(params.Validate(), std::invalid_argument);
  params = GapMissionParams{};
  params.recovery_odometry_delay_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(params.Validate(), std::invalid_argument);
  params.recovery_odometry_delay_s = 1e9;  // the IMU alone
  EXPECT_NO_THROW(params.Validate());
  params.recovery_odometry_velocity_sigma_mps = 0.0;
  EXPECT_THROW(params.Validate(), std::invalid_argument);
  params = GapMissionParams{};
  params.recovery_range_sigma_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(params.Validate(), std::invalid_argument);
  params.recovery_range_sigma_m = std::numeric_limits<double>::infinity();  // not fused
  EXPECT_NO_THROW(params.Validate());
  EXPECT_THROW(
      GapMission(GapMissionParams{}, nullptr, ForwardCameraMount(), control::VehicleParameters{}),
      std::invalid_argument);
  Eigen::Isometry3d scaled = ForwardCameraMount();
  scaled.linear() *= 2.0;
  EXPECT_THROW(GapMission(GapMissionParams{}, test_support::Pinhole752x480(), scaled,
                          control::VehicleParameters{}),
               std::invalid_argument);
}

TEST(GapMissionParamsTest, LoadsTheMissionSectionStrictly) {
  const config::ConfigTree tree = config::ConfigTree::FromCommandLine(
      "", {},
      {"mission.hover_s=0.5", "mission.approach.duration_count=4", "mission.detector.canny_low=30",
       "mission.filter.mahalanobis_gate=30", "mission.fallback_limits.max_body_rate_radps=8"});
  config::ParamReader root = tree.Reader();
  GapMissionParams params;
  root.ReadSection("mission", &params);
  EXPECT_DOUBLE_EQ(params.hover_s, 0.5);
  EXPECT_EQ(params.approach.duration_count, 4);
  EXPECT_DOUBLE_EQ(params.detector.canny_low, 30.0);
  EXPECT_DOUBLE_EQ(params.filter.mahalanobis_gate, 30.0);
  EXPECT_DOUBLE_EQ(params.fallback_limits.max_body_rate_radps, 8.0);
  EXPECT_DOUBLE_EQ(params.start_hold_s, GapMissionParams{}.start_hold_s);  // untouched default

  for (const char* bad : {"mission.hover_sec=1", "mission.hover_s=-1"}) {
    const config::ConfigTree bad_tree = config::ConfigTree::FromCommandLine("", {}, {bad});
    config::ParamReader bad_root = bad_tree.Reader();
    GapMissionParams ignored;
    try {
      bad_root.ReadSection("mission", &ignored);
      FAIL() << "expected std::invalid_argument for " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("hover_s"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace aperture::planning
