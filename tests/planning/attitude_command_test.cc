// Attitude command (seed 003 (35)-(36)): the thrust axis of Rz(psi) Ry(theta) Rx(phi) points along
// the commanded acceleration plus gravity for any heading; hover gives level attitude; free fall
// (z'' = -g) is the model's singularity.
#include "planning/mono_nav/attitude_command.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace aperture::planning {
namespace {

TEST(AttitudeCommand, ThrustAxisPointsAlongAccelerationPlusGravity) {
  const double g = 9.81;
  for (const double psi : {0.0, 0.7, -2.1, 3.0}) {
    for (const Eigen::Vector3d& a :
         {Eigen::Vector3d(1.5, 0.0, 0.0), Eigen::Vector3d(0.0, -2.0, 0.5),
          Eigen::Vector3d(-3.0, 2.5, -4.0)}) {
      const std::optional<AttitudeCommand> command = AttitudeFromAcceleration(a, psi, g);
      ASSERT_TRUE(command.has_value());
      const Eigen::Matrix3d R_WB =
          (Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(command->pitch_rad, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(command->roll_rad, Eigen::Vector3d::UnitX()))
              .toRotationMatrix();
      const Eigen::Vector3d thrust_W = (a + Eigen::Vector3d(0, 0, g)).normalized();
      EXPECT_LT((R_WB.col(2) - thrust_W).norm(), 1e-12) << "psi " << psi << " a " << a.transpose();
      EXPECT_DOUBLE_EQ(command->climb_acceleration_mps2, a.z());
    }
  }
}

TEST(AttitudeCommand, HoverIsLevelAndFreeFallIsSingular) {
  const std::optional<AttitudeCommand> hover =
      AttitudeFromAcceleration(Eigen::Vector3d::Zero(), 1.0);
  ASSERT_TRUE(hover.has_value());
  EXPECT_DOUBLE_EQ(hover->roll_rad, 0.0);
  EXPECT_DOUBLE_EQ(hover->pitch_rad, 0.0);
  EXPECT_FALSE(AttitudeFromAcceleration(Eigen::Vector3d(1.0, 0.0, -9.81), 0.0).has_value());
  EXPECT_FALSE(AttitudeFromAcceleration(Eigen::Vector3d(0.0, 0.0, -12.0), 0.0).has_value());
}

}  // namespace
}  // namespace aperture::planning
