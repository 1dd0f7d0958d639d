#include "servo/gap_servo.h"

#include <gtest/gtest.h>

#include <vector>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

std::vector<Eigen::Vector2d> Opening(const Eigen::Vector2d& shift, double scale) {
  std::vector<Eigen::Vector2d> contour = {{0.3, 0.05}, {0.1, 0.2}, {-0.25, 0.1}, {-0.2, -0.15}};
  for (Eigen::Vector2d& p : contour) p = scale * p + shift;
  return contour;
}

// Each law reads its own part of the view and gives what the law itself gives.
TEST(GapServoTest, SelectedLawDrivesTheStep) {
  const Eigen::Isometry3d T_BC = testing::ForwardCameraMount();
  OpeningView view;
  view.t_s = 0.5;
  view.contour_n = Opening({0.1, -0.05}, 0.8);
  view.safe_point_n = Eigen::Vector2d(-0.05, 0.02);

  GapServoParams params;  // law: moments
  GapServo gap(params, T_BC, 0.5);
  gap.SetDesired(Opening({0.0, 0.0}, 1.0), 2.0);
  MomentServo moments(params.moments, T_BC);
  moments.SetDesired(Opening({0.0, 0.0}, 1.0), 2.0);
  const ServoStepResult from_gap = gap.Step(view);
  EXPECT_EQ(gap.law(), GapServoLaw::kMoments);
  EXPECT_LT((from_gap.reference.v_B - moments.Step(view.contour_n).reference.v_B).norm(), 1e-15);
  EXPECT_EQ(from_gap.error.size(), 3);

  params.law = GapServoLaw::kPid;
  GapServo gap_pid(params, T_BC, 0.5);
  gap_pid.SetDesired(Opening({0.0, 0.0}, 1.0), 2.0);  // no effect on the PID
  PidServo pid(params.pid, T_BC, 0.5);
  const ServoStepResult from_pid = gap_pid.Step(view);
  EXPECT_LT((from_pid.reference.v_B - pid.Step(view.t_s, view.safe_point_n).reference.v_B).norm(),
            1e-15);
  EXPECT_EQ(from_pid.error.size(), 2);
  EXPECT_STREQ(ToString(GapServoLaw::kPid), "pid");
}

}  // namespace
}  // namespace aperture::servo
