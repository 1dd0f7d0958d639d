#include "sim/sitl/collision_checker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

namespace aperture::sim {
namespace {

control::QuadState StateAtPosition(const Eigen::Vector3d& p_W, double roll_rad = 0.0) {
  control::QuadState state;
  state.p_WB = p_W;
  state.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()));
  return state;
}

class CollisionCheckerTest : public ::testing::Test {
 protected:
  QuadrotorDynamicsParams dynamics_;  // arm 0.178 m: rotors at +-0.1259 m in x and y; ground z = 0
  CollisionParams params_;            // body 0.08 m, propellers 0.0635 m
};

TEST_F(CollisionCheckerTest, LevelVehicleHitsGroundWithItsBodySphere) {
  const CollisionChecker checker(dynamics_, params_);
  const Eigen::Vector3d p(1.0, 2.0, 0.081);
  EXPECT_FALSE(checker.Check(nullptr, StateAtPosition(p), p).has_value());
  const Eigen::Vector3d low(1.0, 2.0, 0.079);
  const std::optional<Collision> hit = checker.Check(nullptr, StateAtPosition(low), low);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->object_name, "ground");
  EXPECT_EQ(hit->part, "body");
  EXPECT_TRUE(hit->contact_p_W.isApprox(Eigen::Vector3d(1.0, 2.0, 0.0)));
}

TEST_F(CollisionCheckerTest, TiltedVehicleHitsGroundWithAPropellerFirst) {
  const CollisionChecker checker(dynamics_, params_);
  const double roll = 30.0 * M_PI / 180.0;
  // Lowest disk point: rotor centre sin(roll) * l / sqrt(2) below B, disk rim sin(roll) * R more.
  const double drop_m = std::sin(roll) * (dynamics_.vehicle.arm_length_m / std::sqrt(2.0) +
                                          params_.propeller_radius_m);
  ASSERT_GT(drop_m, params_.body_radius_m);  // so the propeller, not the body, is lowest
  const Eigen::Vector3d clear(0.0, 0.0, drop_m + 1e-4);
  EXPECT_FALSE(checker.Check(nullptr, StateAtPosition(clear, roll), clear).has_value());
  const Eigen::Vector3d low(0.0, 0.0, drop_m - 1e-4);
  const std::optional<Collision> hit = checker.Check(nullptr, StateAtPosition(low, roll), low);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->part.rfind("propeller", 0), 0u) << hit->part;
  EXPECT_DOUBLE_EQ(hit->contact_p_W.z(), 0.0);
  // Rolling by +30 deg about x lowers the -y_B side: the contact is the rim point of a -y_B rotor.
  EXPECT_NEAR(hit->contact_p_W.y(),
              -std::cos(roll) *
                  (dynamics_.vehicle.arm_length_m / std::sqrt(2.0) + params_.propeller_radius_m),
              1e-9);
}

TEST_F(CollisionCheckerTest, DetectsAWallWithinTheBodyRadiusOnly) {
  Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(0.0, 0.0, 5.0);
  // A ceiling plate above the vehicle: only the body sphere can reach it (the rotor plane is
  // level), so the detection distance is the body radius.
  scene.AddObject({"ceiling", Box{Eigen::Vector3d(2.0, 2.0, 0.1)}, Material{}, T_WO});
  params_.ground_enabled = false;
  const CollisionChecker checker(dynamics_, params_);
  const Eigen::Vector3d far(0.0, 0.0, 4.95 - params_.body_radius_m - 0.005);
  EXPECT_FALSE(checker.Check(&scene, StateAtPosition(far), far).has_value());
  // Fibonacci rays: the best one is within ~15 deg of the normal for 64 rays, so a surface
  // at 0.9 radius is always seen.
  const Eigen::Vector3d near(0.0, 0.0, 4.95 - 0.9 * params_.body_radius_m);
  const std::optional<Collision> hit = checker.Check(&scene, StateAtPosition(near), near);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->object_name, "ceiling");
  EXPECT_EQ(hit->part, "body");
  EXPECT_NEAR(hit->contact_p_W.z(), 4.95, 1e-9);
  // An ignored object is transparent to the check.
  params_.ignored_objects = {"ceiling"};
  const CollisionChecker ignoring(dynamics_, params_);
  EXPECT_FALSE(ignoring.Check(&scene, StateAtPosition(near), near).has_value());
}

TEST_F(CollisionCheckerTest, PropellerDiskHitsASceneObjectBeyondTheBodyAndArm) {
  // A wall face 4 cm outside the rotor in the +x+y quadrant, covering y >= 0.1 m only: out of
  // reach of the body sphere (0.19 m away) and of the arms (they end at the rotor centre), but
  // inside that rotor's 6.35 cm disk. Level vehicle, so the disk ray along +x_B hits it first.
  int rotor = -1;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r = dynamics_.vehicle.RotorPosition_B(i);
    if (r.x() > 0.0 && r.y() > 0.0) rotor = i;
  }
  ASSERT_GE(rotor, 0);
  const Eigen::Vector3d r_B = dynamics_.vehicle.RotorPosition_B(rotor);
  const double face_x = r_B.x() + 0.04;
  Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(face_x + 0.1, 0.6, 2.0);
  scene.AddObject({"wall", Box{Eigen::Vector3d(0.2, 1.0, 1.0)}, Material{}, T_WO});
  params_.ground_enabled = false;
  const CollisionChecker checker(dynamics_, params_);
  const Eigen::Vector3d p(0.0, 0.0, 2.0);
  const std::optional<Collision> hit = checker.Check(&scene, StateAtPosition(p), p);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->object_name, "wall");
  EXPECT_EQ(hit->part, "propeller " + std::to_string(rotor + 1));
  EXPECT_TRUE(hit->contact_p_W.isApprox(Eigen::Vector3d(face_x, r_B.y(), 2.0), 1e-9))
      << hit->contact_p_W.transpose();
  // 3 cm further out the disk (radius 6.35 cm) no longer reaches it.
  T_WO.translation().x() += 0.03;
  Scene farther;
  farther.AddObject({"wall", Box{Eigen::Vector3d(0.2, 1.0, 1.0)}, Material{}, T_WO});
  EXPECT_FALSE(checker.Check(&farther, StateAtPosition(p), p).has_value());
}

TEST_F(CollisionCheckerTest, SweepCatchesTunnellingThroughAThinPlate) {
  Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T_WO.translation() = Eigen::Vector3d(1.0, 0.0, 2.0);
  Rectangle plate;
  plate.size_m = Eigen::Vector2d(2.0, 2.0);
  scene.AddObject({"plate", plate, Material{}, T_WO});  // the plane x_W = 1
  const CollisionChecker checker(dynamics_, params_);
  // Both positions 0.5 m from the plate, on opposite sides: only the swept segment crosses it.
  const Eigen::Vector3d before(0.5, 0.0, 2.0), after(1.5, 0.0, 2.0);
  EXPECT_FALSE(checker.Check(&scene, StateAtPosition(after), after).has_value());
  const std::optional<Collision> hit = checker.Check(&scene, StateAtPosition(after), before);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->part, "sweep");
  EXPECT_NEAR(hit->contact_p_W.x(), 1.0, 1e-9);
}

TEST_F(CollisionCheckerTest, BroadPhaseKeepsFarCentredWallsAndSweptSmallPlates) {
  // Objects are ray-tested only when their bounding sphere comes within the vehicle's reach of the
  // swept segment; these two are hit although their centres are far from both end positions.
  Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // A 3 x 20 m wall in the plane x_W = 1 spanning y_W in [-0.1, 19.9]: centre 9.9 m away.
  T_WO.translation() = Eigen::Vector3d(1.0, 9.9, 2.0);
  Rectangle wall;
  wall.size_m = Eigen::Vector2d(3.0, 20.0);
  scene.AddObject({"wall", wall, Material{}, T_WO});
  // A 0.2 m plate in the plane x_W = -1 (the end positions below are 1 m from it).
  T_WO.translation() = Eigen::Vector3d(-1.0, 0.0, 2.0);
  Rectangle plate;
  plate.size_m = Eigen::Vector2d(0.2, 0.2);
  scene.AddObject({"plate", plate, Material{}, T_WO});
  params_.ground_enabled = false;
  const CollisionChecker checker(dynamics_, params_);
  const Eigen::Vector3d near_wall(1.0 - 0.9 * params_.body_radius_m, 0.0, 2.0);
  const std::optional<Collision> wall_hit =
      checker.Check(&scene, StateAtPosition(near_wall), near_wall);
  ASSERT_TRUE(wall_hit.has_value());
  EXPECT_EQ(wall_hit->object_name, "wall");
  EXPECT_NEAR(wall_hit->contact_p_W.x(), 1.0, 1e-9);
  const Eigen::Vector3d before(-2.0, 0.0, 2.0), after(0.0, 0.0, 2.0);
  EXPECT_FALSE(checker.Check(&scene, StateAtPosition(after), after).has_value());
  const std::optional<Collision> plate_hit = checker.Check(&scene, StateAtPosition(after), before);
  ASSERT_TRUE(plate_hit.has_value());
  EXPECT_EQ(plate_hit->object_name, "plate");
  EXPECT_EQ(plate_hit->part, "sweep");
  EXPECT_NEAR(plate_hit->contact_p_W.x(), -1.0, 1e-9);
}

TEST_F(CollisionCheckerTest, RejectsNonPositiveRadius) {
  params_.body_radius_m = 0.0;
  EXPECT_THROW(CollisionChecker(dynamics_, params_), std::invalid_argument);
}

TEST_F(CollisionCheckerTest, TouchdownBeyondTheLimitsIsAGroundCollision) {
  dynamics_.ground_contact_enabled = true;
  dynamics_.ground_height_m = 0.5;
  dynamics_.landing_gear_height_m = 0.1;
  params_.max_touchdown_speed_mps = 1.0;
  params_.max_touchdown_tilt_rad = 0.4;
  const CollisionChecker checker(dynamics_, params_);
  const Eigen::Vector3d p(1.0, 2.0, 0.6);  // resting on the gear: clear of the ground
  EXPECT_FALSE(checker.Check(nullptr, StateAtPosition(p), p).has_value());
  EXPECT_FALSE(checker.CheckTouchdown(p, 0.9, 0.3).has_value());
  for (const auto& [speed, tilt] : {std::pair{1.1, 0.0}, std::pair{0.2, 0.5}}) {
    const std::optional<Collision> hit = checker.CheckTouchdown(p, speed, tilt);
    ASSERT_TRUE(hit.has_value()) << speed << " m/s, " << tilt << " rad";
    EXPECT_EQ(hit->object_name, "ground");
    EXPECT_EQ(hit->part, "landing gear");
    EXPECT_TRUE(hit->contact_p_W.isApprox(Eigen::Vector3d(1.0, 2.0, 0.5)));
  }
  params_.ground_enabled = false;  // no solid ground: nothing to crash into
  EXPECT_FALSE(CollisionChecker(dynamics_, params_).CheckTouchdown(p, 5.0, 1.0).has_value());
}

TEST_F(CollisionCheckerTest, RejectsLandingGearShorterThanTheBodyRadius) {
  dynamics_.ground_contact_enabled = true;
  dynamics_.landing_gear_height_m = params_.body_radius_m;
  EXPECT_THROW(CollisionChecker(dynamics_, params_), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
