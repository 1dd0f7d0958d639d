// The footprint check against closed-form clearances: the body sphere, a propeller disk and the
// panel's outer edge, each just inside and just beyond its limit.
#include "experiments/gap/gap_footprint.h"

#include <gtest/gtest.h>

#include <cmath>

#include "control/constants.h"
#include "perception/camera/optical_axes.h"

namespace aperture::experiments {
namespace {

using control::kDegToRad;

// The upright gap of the scenario at (5, 0, 1.5): x_G = -y_W (long side, 0.8 m), y_G = -z_W
// (short side, 0.28 m), z_G = x_W (the flight direction).
GapGeometry UprightGapGeometry() {
  GapGeometry gap;
  gap.T_WG.linear() = perception::OpticalAxesAlongX();
  gap.T_WG.translation() = Eigen::Vector3d(5.0, 0.0, 1.5);
  return gap;
}

// Level flight along x_W at 2 m/s through the gap plane, offset by (x_G, y_G), at a constant
// attitude; 1 kHz samples from 0.5 m before to 0.5 m after the plane (or only those two ends).
std::vector<control::QuadState> LevelPassThroughGap(const GapGeometry& gap,
                                                    const Eigen::Vector2d& offset_G,
                                                    const Eigen::Quaterniond& q_WB,
                                                    bool only_ends = false) {
  std::vector<control::QuadState> trajectory;
  const int samples = only_ends ? 1 : 500;
  for (int k = 0; k <= samples; ++k) {
    control::QuadState s;
    s.t_s = 0.5 * k / samples;
    s.p_WB = gap.T_WG * Eigen::Vector3d(offset_G.x(), offset_G.y(), -0.5 + 2.0 * s.t_s);
    s.v_W = Eigen::Vector3d(2.0, 0.0, 0.0);
    s.q_WB = q_WB;
    trajectory.push_back(s);
  }
  return trajectory;
}

const VehicleFootprint kDefaultVehicleFootprint =
    VehicleFootprintOf(control::VehicleParameters{}, sim::CollisionParams{});

TEST(VehicleFootprint, TakesTheSitlCollisionGeometry) {
  EXPECT_DOUBLE_EQ(kDefaultVehicleFootprint.body_radius_m, 0.08);
  EXPECT_DOUBLE_EQ(kDefaultVehicleFootprint.propeller_radius_m, 0.0635);
  EXPECT_NEAR(kDefaultVehicleFootprint.rotor_p_B[0].norm(), 0.178, 1e-12);
  EXPECT_NEAR(kDefaultVehicleFootprint.ReachM(), 0.178 + 0.0635, 1e-12);
}

TEST(FindFootprintContact, TheBodySphereClearsTheShortSideByItsRadius) {
  const GapGeometry gap = UprightGapGeometry();
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  // Short side half 0.14 m, sphere 0.08 m: 6 cm of clearance up and down.
  EXPECT_FALSE(FindFootprintContact(LevelPassThroughGap(gap, {0.0, 0.059}, level), gap,
                                    kDefaultVehicleFootprint));
  EXPECT_FALSE(FindFootprintContact(LevelPassThroughGap(gap, {0.0, -0.059}, level), gap,
                                    kDefaultVehicleFootprint));
  const auto contact = FindFootprintContact(LevelPassThroughGap(gap, {0.0, 0.061}, level), gap,
                                            kDefaultVehicleFootprint);
  ASSERT_TRUE(contact.has_value());
  EXPECT_EQ(contact->part, "body");
  EXPECT_GE(std::abs(contact->p_G_m.y()), 0.14);  // on the panel, below the opening
}

TEST(FindFootprintContact, APropellerDiskClearsTheLongSideByArmPlusRadius) {
  const GapGeometry gap = UprightGapGeometry();
  // Yawed 45 deg: rotors 1 and 3 lie on the flight direction, 2 and 4 sideways at 0.178 m, their
  // disks reaching 0.178 + 0.0635 = 0.2415 m out; the long side's half is 0.4 m.
  const Eigen::Quaterniond yawed(Eigen::AngleAxisd(45.0 * kDegToRad, Eigen::Vector3d::UnitZ()));
  const double limit = 0.4 - 0.2415;
  EXPECT_FALSE(FindFootprintContact(LevelPassThroughGap(gap, {limit - 0.001, 0.0}, yawed), gap,
                                    kDefaultVehicleFootprint));
  const auto contact = FindFootprintContact(LevelPassThroughGap(gap, {limit + 0.001, 0.0}, yawed),
                                            gap, kDefaultVehicleFootprint);
  ASSERT_TRUE(contact.has_value());
  EXPECT_EQ(contact->part.rfind("propeller", 0), 0u) << contact->part;
  EXPECT_GE(contact->p_G_m.x(), 0.4);
}

TEST(FindFootprintContact, TestsBetweenSamplesSoNothingPassesBetweenThem) {
  const GapGeometry gap = UprightGapGeometry();
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  // Two samples 0.5 m either side of the plane: the sphere's passage lies between them.
  const auto contact =
      FindFootprintContact(LevelPassThroughGap(gap, {0.0, 0.1}, level, /*only_ends=*/true), gap,
                           kDefaultVehicleFootprint);
  ASSERT_TRUE(contact.has_value());
  EXPECT_EQ(contact->part, "body");
  EXPECT_GT(contact->t_s, 0.2);
  EXPECT_LT(contact->t_s, 0.3);
  EXPECT_FALSE(
      FindFootprintContact(LevelPassThroughGap(gap, {0.0, 0.03}, level, /*only_ends=*/true), gap,
                           kDefaultVehicleFootprint));
}

TEST(FindFootprintContact, NothingToHitBeyondThePanel) {
  const GapGeometry gap = UprightGapGeometry();  // panel 1.7 x 1.2 m
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  EXPECT_FALSE(FindFootprintContact(LevelPassThroughGap(gap, {1.2, 0.0}, level), gap,
                                    kDefaultVehicleFootprint));
  // Overlapping the panel's outer edge (at 0.85 m) by 1 cm or more is a contact.
  const auto edge = FindFootprintContact(LevelPassThroughGap(gap, {0.85 + 0.07, 0.0}, level), gap,
                                         kDefaultVehicleFootprint);
  ASSERT_TRUE(edge.has_value());
  EXPECT_LE(edge->p_G_m.x(), 0.85);
}

TEST(FindFootprintContact, ATiltedDiskIsCutAlongItsChord) {
  const GapGeometry gap = UprightGapGeometry();
  // Rolled 90 deg about the flight direction: the rotor plane is vertical (x_W, z_W) and the
  // disks' chords in the panel plane run along y_G (the short side). Yawed 45 deg first, rotors
  // 2 and 4 stand 0.178 m above and below B: the disks reach 0.2415 m, beyond the 0.14 m half
  // side, so the vehicle cannot pass upright like this; turned so the rotor plane lies along the
  // long side (roll 0) it can.
  const Eigen::Quaterniond rolled(Eigen::AngleAxisd(90.0 * kDegToRad, Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(45.0 * kDegToRad, Eigen::Vector3d::UnitZ()));
  const auto contact = FindFootprintContact(LevelPassThroughGap(gap, {0.0, 0.0}, rolled), gap,
                                            kDefaultVehicleFootprint);
  ASSERT_TRUE(contact.has_value());
  EXPECT_EQ(contact->part.rfind("propeller", 0), 0u) << contact->part;
  EXPECT_GE(std::abs(contact->p_G_m.y()), 0.14);
  EXPECT_LE(std::abs(contact->p_G_m.y()), 0.2415 + 1e-9);
}

TEST(FindFootprintContact, RejectsInvalidInput) {
  GapGeometry gap = UprightGapGeometry();
  const auto pass = LevelPassThroughGap(gap, {0.0, 0.0}, Eigen::Quaterniond::Identity());
  EXPECT_THROW(FindFootprintContact(pass, gap, kDefaultVehicleFootprint, 0.0),
               std::invalid_argument);
  VehicleFootprint no_body = kDefaultVehicleFootprint;
  no_body.body_radius_m = 0.0;
  EXPECT_THROW(FindFootprintContact(pass, gap, no_body), std::invalid_argument);
  gap.panel_m = Eigen::Vector2d(0.5, 1.2);  // narrower than the 0.8 m opening
  EXPECT_THROW(FindFootprintContact(pass, gap, kDefaultVehicleFootprint), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
