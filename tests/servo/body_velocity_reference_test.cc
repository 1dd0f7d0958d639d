#include "servo/body_velocity_reference.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

TEST(BodyVelocityReferenceTest, ForwardCameraTwistMapsToTheHandComputedBodyVelocity) {
  // Forward camera 0.1 m ahead of the body origin (x_C = -y_B, y_C = -z_B, z_C = x_B). The
  // camera moves right 0.2, up 0.1 (y_C = -0.1), forward 0.5 m/s and turns left at 0.3 rad/s
  // (omega about -y_C = +z_B). Body: v = (0.5, -0.2, 0.1) from the camera's motion, plus the
  // lever arm: the origin 0.1 m behind a left-turning camera moves right, 0.1 * 0.3 = 0.03 m/s.
  Twist twist_C;
  twist_C << 0.2, -0.1, 0.5, 0.0, -0.3, 0.0;
  const BodyVelocityReference body =
      BodyVelocityFromCameraTwist(twist_C, testing::ForwardCameraMount());
  EXPECT_NEAR(body.v_B.x(), 0.5, 1e-15);
  EXPECT_NEAR(body.v_B.y(), -0.23, 1e-15);
  EXPECT_NEAR(body.v_B.z(), 0.1, 1e-15);
  EXPECT_NEAR(body.yaw_rate_radps, 0.3, 1e-15);
}

TEST(BodyVelocityReferenceTest, TwistMatricesComposeAndInvert) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int n = 0; n < 20; ++n) {
    Eigen::Isometry3d T_AB = Eigen::Isometry3d::Identity();
    T_AB.linear() = Eigen::AngleAxisd(3.0 * unit(rng),
                                      Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized())
                        .toRotationMatrix();
    T_AB.translation() = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    Eigen::Isometry3d T_BC = T_AB;
    T_BC.translation() *= -0.5;
    // twist_A = V(T_AB) V(T_BC) twist_C = V(T_AC) twist_C; V(T_BA) = V(T_AB)^-1.
    EXPECT_LT(
        (VelocityTwistMatrix(T_AB) * VelocityTwistMatrix(T_BC) - VelocityTwistMatrix(T_AB * T_BC))
            .cwiseAbs()
            .maxCoeff(),
        1e-12);
    EXPECT_LT((VelocityTwistMatrix(T_AB) * VelocityTwistMatrix(T_AB.inverse()) -
               Eigen::Matrix<double, 6, 6>::Identity())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
    // Body references survive the round trip through the camera twist (no roll/pitch rate).
    BodyVelocityReference body;
    body.v_B = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    body.yaw_rate_radps = unit(rng);
    const BodyVelocityReference back =
        BodyVelocityFromCameraTwist(CameraTwistFromBodyVelocity(body, T_AB), T_AB);
    EXPECT_LT((back.v_B - body.v_B).norm(), 1e-12);
    EXPECT_NEAR(back.yaw_rate_radps, body.yaw_rate_radps, 1e-12);
  }
}

TEST(BodyVelocityReferenceTest, RejectsNonFiniteInput) {
  Twist twist_C = Twist::Zero();
  twist_C[2] = NAN;
  EXPECT_THROW(BodyVelocityFromCameraTwist(twist_C, testing::ForwardCameraMount()),
               std::invalid_argument);
  Eigen::Isometry3d T_BC = testing::ForwardCameraMount();
  T_BC.translation().x() = INFINITY;
  EXPECT_THROW(BodyVelocityFromCameraTwist(Twist::Zero(), T_BC), std::invalid_argument);
  EXPECT_THROW(RequireRigidMount(T_BC, "test"), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::servo
