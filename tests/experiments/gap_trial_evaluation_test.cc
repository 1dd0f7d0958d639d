// Gap crossing, Table I errors and success criteria against synthetic flights whose answer is
// known in closed form.
#include "experiments/gap/gap_trial_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "control/attitude_controller.h"
#include "control/constants.h"
#include "perception/camera/optical_axes.h"

namespace aperture::experiments {
namespace {

using control::kDegToRad;

// The SITL's default collision geometry (0.08 m body sphere, 5 inch propellers, 0.178 m arms).
const VehicleFootprint kSitlFootprint =
    VehicleFootprintOf(control::VehicleParameters{}, sim::CollisionParams{});

// The scenario's gap frame at roll/pitch (sim/scenario/scenario_params.h): x_G = -y_W,
// y_G = -z_W, z_G = x_W at zero angles, then rotated about y_W (pitch) and x_W (roll).
Eigen::Isometry3d GapPoseW(double roll_deg, double pitch_deg, const Eigen::Vector3d& p_WG) {
  const Eigen::Matrix3d R_facing = perception::OpticalAxesAlongX();
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  T_WG.linear() = (Eigen::AngleAxisd(pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix() *
                  R_facing;
  T_WG.translation() = p_WG;
  return T_WG;
}

planning::GapPose ToGapPose(const Eigen::Isometry3d& T_WG) {
  planning::GapPose gap;
  gap.p_WG = T_WG.translation();
  gap.R_WG = T_WG.linear();
  return gap;
}

// Straight flight at constant velocity and attitude through p_cross at t_cross, 1 kHz samples
// over [0, duration].
std::vector<control::QuadState> Line(const Eigen::Vector3d& p_cross, const Eigen::Vector3d& v_W,
                                     double t_cross, double duration_s,
                                     const Eigen::Quaterniond& q_WB) {
  std::vector<control::QuadState> trajectory;
  for (int k = 0; k <= static_cast<int>(std::lround(duration_s * 1000.0)); ++k) {
    control::QuadState s;
    s.t_s = k * 1e-3;
    s.p_WB = p_cross + (s.t_s - t_cross) * v_W;
    s.v_W = v_W;
    s.q_WB = q_WB;
    trajectory.push_back(s);
  }
  return trajectory;
}

TEST(FindGapCrossing, FindsTheTimeAndPointOfAnInclinedLineCrossing) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(30.0, 10.0, Eigen::Vector3d(5.0, 0.2, 1.5));
  // Crosses at (x_G, y_G) = (0.1, -0.05) at t = 1.2345 s (between two 1 kHz samples), moving
  // along z_G and sideways.
  const Eigen::Vector3d p_cross = gap.T_WG * Eigen::Vector3d(0.1, -0.05, 0.0);
  const Eigen::Vector3d v_W = gap.T_WG.linear() * Eigen::Vector3d(0.3, 0.1, 2.5);
  const auto trajectory = Line(p_cross, v_W, 1.2345, 3.0, Eigen::Quaterniond::Identity());
  const std::optional<GapCrossing> crossing = FindGapCrossing(trajectory, gap);
  ASSERT_TRUE(crossing.has_value());
  // Linear motion is interpolated exactly: only rounding remains.
  EXPECT_NEAR(crossing->t_s, 1.2345, 1e-9);
  EXPECT_NEAR(crossing->p_G_m.x(), 0.1, 1e-9);
  EXPECT_NEAR(crossing->p_G_m.y(), -0.05, 1e-9);
  EXPECT_TRUE(crossing->inside_opening);
  EXPECT_LT((crossing->state.p_WB - p_cross).norm(), 1e-9);
}

TEST(FindGapCrossing, TellsInsideFromOutsideOfTheOpeningAndIgnoresBackwardCrossings) {
  GapGeometry gap;  // 0.8 x 0.28 m opening
  gap.T_WG = GapPoseW(45.0, 0.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  const Eigen::Vector3d along_W = gap.T_WG.linear() * Eigen::Vector3d(0, 0, 2.0);
  const auto through = [&](double x_G, double y_G) {
    return FindGapCrossing(Line(gap.T_WG * Eigen::Vector3d(x_G, y_G, 0.0), along_W, 1.0, 2.0,
                                Eigen::Quaterniond::Identity()),
                           gap);
  };
  EXPECT_TRUE(through(0.39, 0.13)->inside_opening);
  EXPECT_FALSE(through(0.41, 0.0)->inside_opening);   // beyond the long side's half width 0.4
  EXPECT_FALSE(through(0.0, -0.15)->inside_opening);  // beyond the short side's 0.14
  // Flying the other way (from z_G > 0 to z_G < 0) is not a traversal.
  EXPECT_FALSE(
      FindGapCrossing(
          Line(gap.T_WG.translation(), -along_W, 1.0, 2.0, Eigen::Quaterniond::Identity()), gap)
          .has_value());
}

TEST(ComputeErrorAtGap, MapsTheDesiredStateFromTheEstimatedOntoTheTrueGap) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(30.0, 10.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  // The plan's gap estimate is off by 7 cm and 3 deg of yaw: the error must not contain that
  // offset, only the deviation from the plan relative to each gap.
  Eigen::Isometry3d T_est = Eigen::Isometry3d::Identity();
  T_est.linear() = Eigen::AngleAxisd(3.0 * kDegToRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_est.translation() = Eigen::Vector3d(0.05, -0.04, 0.03);
  const Eigen::Isometry3d T_WG_est = T_est * gap.T_WG;
  const planning::TraverseTrajectory plan(ToGapPose(T_WG_est), 1.0, 0.5, 9.81);
  // The plan's apex is the (estimated) gap centre at t_c, with the velocity along e2 only.
  ASSERT_LT((plan.Position(plan.time_to_gap_s()) - T_WG_est.translation()).norm(), 1e-9);
  const double v2 = plan.Velocity(plan.time_to_gap_s()).dot(plan.e2_W());

  // Actual: through (x_G, y_G) = (0.03, -0.02) of the true gap, 0.2 m/s faster along z_G plus
  // 0.1 m/s along x_G, at t = 2.0 s, 20 ms later than the plan's start + t_c.
  const Eigen::Vector3d p_cross = gap.T_WG * Eigen::Vector3d(0.03, -0.02, 0.0);
  const Eigen::Vector3d v_W = gap.T_WG.linear() * Eigen::Vector3d(0.1, 0.0, v2 + 0.2);
  const Eigen::Matrix3d R_desired_true =
      (gap.T_WG * T_WG_est.inverse()).linear() *
      control::ComputeDesiredAttitude(plan.thrust_direction_W(), plan.heading_rad());
  const auto trajectory = Line(p_cross, v_W, 2.0, 3.0, Eigen::Quaterniond(R_desired_true));
  const std::optional<GapCrossing> crossing = FindGapCrossing(trajectory, gap);
  ASSERT_TRUE(crossing.has_value());
  const GapStateError error =
      ComputeErrorAtGap(crossing->state, crossing, gap, plan, 2.0 - plan.time_to_gap_s() - 0.02);

  const Eigen::Vector3d expected_p = gap.T_WG.linear() * Eigen::Vector3d(0.03, -0.02, 0.0);
  const Eigen::Vector3d expected_v = gap.T_WG.linear() * Eigen::Vector3d(0.1, 0.0, 0.2);
  // Exact maps; 1e-9 covers rounding in the interpolation and the rotations.
  EXPECT_LT((error.position_m - expected_p).norm(), 1e-9);
  EXPECT_LT((error.velocity_mps - expected_v).norm(), 1e-9);
  EXPECT_LT(error.orientation_deg.norm(), 1e-6);  // attitude = desired attitude
  EXPECT_NEAR(error.time_s, 0.02, 1e-9);
}

TEST(ComputeErrorAtGap, OrientationErrorIsRollAndPitchOfTheDifference) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(0.0, 0.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  // Upright gap, start straight in front: thrust along +z_W, heading 0 -> desired R = I.
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);
  ASSERT_LT((control::ComputeDesiredAttitude(plan.thrust_direction_W(), plan.heading_rad()) -
             Eigen::Matrix3d::Identity())
                .norm(),
            1e-9);
  // R = Ry(pitch) Rx(roll): ZYX angles without yaw are exactly (roll, pitch).
  const Eigen::Quaterniond q(Eigen::AngleAxisd(-3.0 * kDegToRad, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(5.0 * kDegToRad, Eigen::Vector3d::UnitX()));
  const auto trajectory = Line(gap.T_WG.translation(), Eigen::Vector3d(3.0, 0, 0), 1.0, 2.0, q);
  const std::optional<GapCrossing> crossing = FindGapCrossing(trajectory, gap);
  const GapStateError error = ComputeErrorAtGap(crossing->state, crossing, gap, plan, 0.5);
  EXPECT_NEAR(error.orientation_deg.x(), 5.0, 1e-9);
  EXPECT_NEAR(error.orientation_deg.y(), -3.0, 1e-9);
}

// A flight through the gap centre that brakes to a hover 1.5 m behind the gap and stays there.
sim::SitlResult ThroughAndHover(const GapGeometry& gap, double final_speed_mps) {
  sim::SitlResult result;
  const Eigen::Vector3d z_G = gap.T_WG.linear().col(2);
  for (int k = 0; k <= 4000; ++k) {
    control::QuadState s;
    s.t_s = k * 1e-3;
    if (s.t_s < 2.0) {  // 2 m/s along z_G, through the centre at t = 1 s
      s.p_WB = gap.T_WG.translation() + (s.t_s - 1.0) * 2.0 * z_G;
      s.v_W = 2.0 * z_G;
    } else {  // then (nearly) still, turning about z_B at 1 rad/s (a heading change)
      s.p_WB = gap.T_WG.translation() + 2.0 * z_G;
      s.v_W = final_speed_mps * z_G;
      s.omega_B = Eigen::Vector3d(0.0, 0.0, 1.0);
    }
    result.trajectory.push_back(s);
  }
  result.sim_time_s = 4.0;
  return result;
}

TEST(EvaluateGapTrial, SucceedsThroughTheOpeningIntoAHover) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(20.0, 5.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);
  const GapTrialEvaluation evaluation =
      EvaluateGapTrial(ThroughAndHover(gap, 0.0), gap, kSitlFootprint, plan, 0.5);
  EXPECT_TRUE(evaluation.success) << evaluation.failure_reason;
  EXPECT_TRUE(evaluation.failure_reason.empty());
  ASSERT_TRUE(evaluation.crossing.has_value());
  EXPECT_NEAR(evaluation.crossing->t_s, 1.0, 1e-9);
  ASSERT_TRUE(evaluation.error.has_value());
  EXPECT_LT(evaluation.error->position_m.norm(), 1e-9);  // through the centre
}

TEST(EvaluateGapTrial, NamesTheFirstFailedCriterion) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(20.0, 5.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);

  // Rocking about x_B at 0.6 rad/s at the end (criterion: 0.5 rad/s roll/pitch rate).
  sim::SitlResult rocking = ThroughAndHover(gap, 0.0);
  rocking.trajectory.back().omega_B.x() = 0.6;
  EXPECT_EQ(EvaluateGapTrial(rocking, gap, kSitlFootprint, plan, 0.5).failure_reason,
            "not hovering at the end: roll/pitch rate 0.60 rad/s at t = 4.00 s");

  // Still moving at 0.5 m/s at the end (criterion: 0.3 m/s).
  GapTrialEvaluation drifting =
      EvaluateGapTrial(ThroughAndHover(gap, 0.5), gap, kSitlFootprint, plan, 0.5);
  EXPECT_FALSE(drifting.success);
  EXPECT_NE(drifting.failure_reason.find("not hovering at the end: speed 0.50 m/s"),
            std::string::npos)
      << drifting.failure_reason;

  sim::SitlResult crashed = ThroughAndHover(gap, 0.0);
  crashed.outcome = sim::SitlResult::Outcome::kCollision;
  crashed.reason = "collision: propeller 2 with 'gap'";
  const GapTrialEvaluation collision = EvaluateGapTrial(crashed, gap, kSitlFootprint, plan, 0.5);
  EXPECT_FALSE(collision.success);
  EXPECT_EQ(collision.failure_reason, "collision: propeller 2 with 'gap'");
  EXPECT_TRUE(collision.error.has_value());  // errors count for failed trials too (Table I)

  sim::SitlResult beside = ThroughAndHover(gap, 0.0);
  for (control::QuadState& s : beside.trajectory) s.p_WB += gap.T_WG.linear().col(0) * 0.5;
  const GapTrialEvaluation outside = EvaluateGapTrial(beside, gap, kSitlFootprint, plan, 0.5);
  EXPECT_EQ(
      outside.failure_reason.rfind("crossed the gap plane outside the opening at x_G = 0.500 m", 0),
      0u)
      << outside.failure_reason;

  sim::SitlResult short_of_gap = ThroughAndHover(gap, 0.0);
  short_of_gap.trajectory.resize(900);  // ends before t = 1 s
  const GapTrialEvaluation never = EvaluateGapTrial(short_of_gap, gap, kSitlFootprint, std::nullopt,
                                                    std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(never.failure_reason, "never crossed the gap plane (no traverse plan)");
  EXPECT_FALSE(never.error.has_value());
}

// Table I by the paper's definition takes the state at the planned t_c: a flight through the gap
// centre 20 ms late has no error at its crossing but is 2 m/s * 20 ms short of the gap at t_c.
TEST(EvaluateGapTrial, TableIErrorIsTakenAtThePlannedTimeOfTheCrossing) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(20.0, 5.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);
  const double traverse_start_s = 1.0 - plan.time_to_gap_s() - 0.02;  // crossing at t = 1 s
  const GapTrialEvaluation evaluation =
      EvaluateGapTrial(ThroughAndHover(gap, 0.0), gap, kSitlFootprint, plan, traverse_start_s);
  ASSERT_TRUE(evaluation.error.has_value() && evaluation.error_at_planned_tc.has_value());
  EXPECT_LT(evaluation.error->position_m.norm(), 1e-9);
  const Eigen::Vector3d expected = -0.04 * gap.T_WG.linear().col(2);  // 2 m/s * 0.02 s short
  EXPECT_LT((evaluation.error_at_planned_tc->position_m - expected).norm(), 1e-9);
  EXPECT_NEAR(evaluation.error_at_planned_tc->time_s, 0.02, 1e-9);
  // The velocity of both is the same flight's (constant speed around the crossing).
  EXPECT_LT((evaluation.error_at_planned_tc->velocity_mps - evaluation.error->velocity_mps).norm(),
            1e-9);

  // A flight that never reached the gap still has its Table I error (the paper counts every
  // flight), with no arrival time.
  sim::SitlResult short_of_gap = ThroughAndHover(gap, 0.0);
  short_of_gap.trajectory.resize(900);
  const GapTrialEvaluation never =
      EvaluateGapTrial(short_of_gap, gap, kSitlFootprint, plan, traverse_start_s);
  EXPECT_FALSE(never.error.has_value());
  ASSERT_TRUE(never.error_at_planned_tc.has_value());
  EXPECT_TRUE(std::isnan(never.error_at_planned_tc->time_s));
  EXPECT_NEAR(never.error_at_planned_tc->position_m.norm(), 2.0 * (1.0 - 0.899),
              1e-9);  // its last state
}

// The origin of B inside the opening is not enough: the body sphere (0.08 m) must clear the
// short side (half 0.14 m).
TEST(EvaluateGapTrial, FailsWhenTheFootprintMeetsThePanel) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(0.0, 0.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);
  sim::SitlResult low = ThroughAndHover(gap, 0.0);
  for (control::QuadState& s : low.trajectory) s.p_WB += gap.T_WG.linear().col(1) * 0.1;
  const GapTrialEvaluation evaluation = EvaluateGapTrial(low, gap, kSitlFootprint, plan, 0.5);
  ASSERT_TRUE(evaluation.crossing.has_value());
  EXPECT_TRUE(evaluation.crossing->inside_opening);
  EXPECT_FALSE(evaluation.success);
  EXPECT_EQ(evaluation.failure_reason.rfind("footprint: body meets the gap panel at x_G = ", 0), 0u)
      << evaluation.failure_reason;
  ASSERT_TRUE(evaluation.footprint_contact.has_value());
  EXPECT_NEAR(evaluation.footprint_contact->t_s, 1.0 - std::sqrt(0.08 * 0.08 - 0.04 * 0.04) / 2.0,
              2e-3);
}

// The pattern looks the same turned by 180 deg about z_G: a mission whose estimate picked the
// other of the two frames flew the same path, and its error must not come out as a half turn.
TEST(ComputeErrorAtGap, UsesTheLookAlikeGapFrameTheEstimateRefersTo) {
  GapGeometry gap;
  gap.T_WG = GapPoseW(20.0, 5.0, Eigen::Vector3d(5.0, 0.0, 1.5));
  Eigen::Isometry3d T_WG_turned = gap.T_WG;
  T_WG_turned.linear() = gap.T_WG.linear() * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  const planning::TraverseTrajectory plan(ToGapPose(gap.T_WG), 1.0, 0.5, 9.81);
  const planning::TraverseTrajectory plan_turned(ToGapPose(T_WG_turned), 1.0, 0.5, 9.81);
  // Both plans are the same arc in the world; mapped without the turn, the second one's velocity
  // would come out mirrored about z_G.
  ASSERT_TRUE(plan.Velocity(plan.time_to_gap_s())
                  .isApprox(plan_turned.Velocity(plan_turned.time_to_gap_s()), 1e-9));
  const sim::SitlResult flight = ThroughAndHover(gap, 0.0);
  const GapTrialEvaluation evaluation = EvaluateGapTrial(flight, gap, kSitlFootprint, plan, 0.5);
  const GapTrialEvaluation turned = EvaluateGapTrial(flight, gap, kSitlFootprint, plan_turned, 0.5);
  ASSERT_TRUE(evaluation.error.has_value() && turned.error.has_value());
  EXPECT_LT((turned.error->position_m - evaluation.error->position_m).norm(), 1e-9);
  EXPECT_LT((turned.error->velocity_mps - evaluation.error->velocity_mps).norm(), 1e-9);
  EXPECT_TRUE(TrueGapMatchingEstimate(gap.T_WG, T_WG_turned.linear()).isApprox(T_WG_turned));
  EXPECT_TRUE(TrueGapMatchingEstimate(gap.T_WG, gap.T_WG.linear()).isApprox(gap.T_WG));
}

TEST(GroundTruthAt, InterpolatesBetweenRecordedStatesAndClampsToTheirSpan) {
  control::QuadState a, b;
  a.t_s = 1.0;
  b.t_s = 2.0;
  b.p_WB = Eigen::Vector3d(1.0, 2.0, 3.0);
  b.v_W = Eigen::Vector3d(0.0, 0.0, 1.0);
  b.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()));
  const std::vector<control::QuadState> trajectory = {a, b};
  const control::QuadState mid = GroundTruthAt(trajectory, 1.25);
  EXPECT_TRUE(mid.p_WB.isApprox(Eigen::Vector3d(0.25, 0.5, 0.75)));
  EXPECT_NEAR(mid.v_W.z(), 0.25, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(mid.q_WB).angle(), 0.25, 1e-12);
  EXPECT_EQ(GroundTruthAt(trajectory, 0.0).t_s, 1.0);
  EXPECT_EQ(GroundTruthAt(trajectory, 5.0).t_s, 2.0);
  EXPECT_THROW(GroundTruthAt({}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
