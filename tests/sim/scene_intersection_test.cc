// Ray intersections against independent constructions: pick a point on the surface, back off
// along a ray that enters the surface there, and expect exactly that distance back.
#include <gtest/gtest.h>

#include <random>

#include "render_test_util.h"
#include "sim/scene/scene.h"

namespace aperture::sim {
namespace {

using testing::Pose;

// Hits are computed in double from closed forms; 1e-9 m allows for rounding over ~10 m.
constexpr double kTolM = 1e-9;

Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// A unit direction d with d . n <= -0.2 (entering the surface with outward normal n).
Eigen::Vector3d EnteringDirection(std::mt19937& rng, const Eigen::Vector3d& n) {
  while (true) {
    const Eigen::Vector3d d = RandomUnit(rng);
    if (d.dot(n) < -0.2) return d;
  }
}

Eigen::Isometry3d RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  return Pose(RandomUnit(rng) * 2.0, Eigen::Vector3d(u(rng), u(rng), u(rng)));
}

struct IntersectionCase {
  Primitive primitive;
  Eigen::Vector3d p_O;  // surface point in O
  Eigen::Vector3d n_O;  // outward normal there
};

void ExpectEntryHit(const IntersectionCase& c, const Eigen::Isometry3d& T_WO, std::mt19937& rng,
                    Eigen::Vector2d* uv_out = nullptr) {
  Scene scene;
  const int id = scene.AddObject({"object", c.primitive, {}, T_WO});
  const Eigen::Vector3d p_W = T_WO * c.p_O;
  const Eigen::Vector3d n_W = T_WO.linear() * c.n_O;
  const Eigen::Vector3d d_W = EnteringDirection(rng, n_W);
  const double distance = std::uniform_real_distribution<double>(0.5, 8.0)(rng);
  const Eigen::Vector3d o_W = p_W - distance * d_W;
  const auto hit = scene.Intersect(o_W, d_W);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t_m, distance, kTolM);
  EXPECT_LT((hit->p_W - p_W).norm(), kTolM);
  EXPECT_EQ(hit->object_id, id);
  EXPECT_LT((hit->n_W - n_W).norm(), 1e-9);  // entering: outward normal faces the origin
  if (uv_out) *uv_out = hit->uv_m;
}

TEST(SceneIntersectionTest, RectangleHitsAtAnalyticPlaneDistanceWithCornerOriginUv) {
  std::mt19937 rng(1);
  for (int i = 0; i < 200; ++i) {
    std::uniform_real_distribution<double> u(-0.9, 0.9);
    const Eigen::Vector3d p_O(u(rng), 0.5 * u(rng), 0.0);
    // Both sides are visible: the side is chosen at random.
    const Eigen::Vector3d n_O = (i % 2 ? 1.0 : -1.0) * Eigen::Vector3d::UnitZ();
    Eigen::Vector2d uv;
    ExpectEntryHit({Rectangle{{2.0, 1.0}, {}, {}}, p_O, n_O}, RandomPose(rng), rng, &uv);
    EXPECT_NEAR(uv.x(), p_O.x() + 1.0, 1e-9);
    EXPECT_NEAR(uv.y(), p_O.y() + 0.5, 1e-9);
  }
}

TEST(SceneIntersectionTest, SphereHitsAtAnalyticDistance) {
  std::mt19937 rng(2);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d n_O = RandomUnit(rng);
    ExpectEntryHit({Sphere{0.7}, 0.7 * n_O, n_O}, RandomPose(rng), rng);
  }
}

TEST(SceneIntersectionTest, CylinderMantleAndCapsHitAtAnalyticDistance) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double phi = 6.283185307179586 * u(rng);
    const Eigen::Vector3d n_O(std::cos(phi), std::sin(phi), 0.0);
    const double z = 0.05 + 2.9 * u(rng);
    Eigen::Vector2d uv;
    ExpectEntryHit({Cylinder{0.2, 3.0}, Eigen::Vector3d(0.2 * n_O.x(), 0.2 * n_O.y(), z), n_O},
                   RandomPose(rng), rng, &uv);
    EXPECT_NEAR(uv.x(), 0.2 * phi, 1e-9);  // arc length around the trunk
    EXPECT_NEAR(uv.y(), z, 1e-9);
  }
  for (int i = 0; i < 100; ++i) {
    const double r = 0.19 * std::sqrt(u(rng));
    const double phi = 6.283185307179586 * u(rng);
    const bool top = i % 2;
    ExpectEntryHit(
        {Cylinder{0.2, 3.0}, Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), top ? 3.0 : 0.0),
         Eigen::Vector3d(0.0, 0.0, top ? 1.0 : -1.0)},
        RandomPose(rng), rng);
  }
}

TEST(SceneIntersectionTest, BoxFacesHitAtAnalyticDistance) {
  std::mt19937 rng(4);
  const Eigen::Vector3d size(0.6, 1.0, 1.4);
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  for (int i = 0; i < 300; ++i) {
    const int axis = i % 3;
    const double sign = (i / 3) % 2 ? 1.0 : -1.0;
    Eigen::Vector3d p_O(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    p_O[axis] = 0.5 * sign * size[axis];
    Eigen::Vector3d n_O = Eigen::Vector3d::Zero();
    n_O[axis] = sign;
    ExpectEntryHit({Box{size}, p_O, n_O}, RandomPose(rng), rng);
  }
}

TEST(SceneIntersectionTest, RayFromInsideABoxHitsTheExitFace) {
  Scene scene;
  scene.AddObject({"room", Box{{4.0, 4.0, 3.0}}, {}, Eigen::Isometry3d::Identity()});
  const auto hit = scene.Intersect(Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t_m, 1.5, kTolM);
  EXPECT_NEAR(hit->n_W.x(), -1.0, 1e-12);  // flipped to face the ray origin
}

TEST(SceneIntersectionTest, GroundPlaneHitsAtAnalyticDistance) {
  Scene scene;
  const int ground = scene.AddObject({"ground", GroundPlane{}, {}, Pose({0, 0, 0}, {0, 0, -0.5})});
  const Eigen::Vector3d o(1.0, 2.0, 1.5);
  const Eigen::Vector3d d = Eigen::Vector3d(1.0, -0.5, -0.8).normalized();
  const auto hit = scene.Intersect(o, d);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t_m, (1.5 + 0.5) / -d.z(), kTolM);
  EXPECT_EQ(hit->object_id, ground);
  EXPECT_FALSE(scene.Intersect(o, Eigen::Vector3d(0.0, 0.0, 1.0)).has_value());  // sky
}

TEST(SceneIntersectionTest, HolesLetRaysThroughToTheObjectBehind) {
  Scene scene;
  Rectangle wall{{3.0, 2.0}, {}, {}};
  // A triangular hole left, a rotated ellipse right.
  wall.polygon_holes.push_back({{-1.2, -0.5}, {-0.4, -0.5}, {-0.8, 0.5}});
  wall.ellipse_holes.push_back({{0.8, 0.0}, {0.4, 0.15}, 0.5});
  // Wall in the plane x_W = 2 (its z_O along +x_W), backdrop at x_W = 5.
  const Eigen::Isometry3d T_WO = Pose({0.0, M_PI / 2, 0.0}, {2.0, 0.0, 0.0});
  const int wall_id = scene.AddObject({"gap", wall, {}, T_WO});
  const int back_id = scene.AddObject({"backdrop",
                                       Rectangle{{20.0, 20.0}, {}, {}},
                                       {},
                                       Pose({0.0, M_PI / 2, 0.0}, {5.0, 0.0, 0.0})});
  auto id_through = [&](const Eigen::Vector2d& q_O) {
    const Eigen::Vector3d target_W = T_WO * Eigen::Vector3d(q_O.x(), q_O.y(), 0.0);
    const auto hit = scene.Intersect(Eigen::Vector3d::Zero(), target_W);
    return hit ? hit->object_id : 0;
  };
  EXPECT_EQ(id_through({-0.8, 0.0}), back_id);    // inside the triangle
  EXPECT_EQ(id_through({-0.8, 0.6}), wall_id);    // above its apex
  EXPECT_EQ(id_through({-0.3, -0.45}), wall_id);  // right of its base corner
  // Ellipse: major axis at 0.5 rad; 0.38 m along it is inside, 0.17 m along the minor is not.
  const Eigen::Vector2d major(std::cos(0.5), std::sin(0.5));
  const Eigen::Vector2d minor(-std::sin(0.5), std::cos(0.5));
  EXPECT_EQ(id_through(Eigen::Vector2d(0.8, 0.0) + 0.38 * major), back_id);
  EXPECT_EQ(id_through(Eigen::Vector2d(0.8, 0.0) + 0.14 * minor), back_id);
  EXPECT_EQ(id_through(Eigen::Vector2d(0.8, 0.0) + 0.17 * minor), wall_id);
  EXPECT_EQ(id_through(Eigen::Vector2d(0.8, 0.0) + 0.42 * major), wall_id);
  EXPECT_EQ(id_through({1.45, 0.95}), wall_id);  // inside the rectangle's corner
  EXPECT_EQ(id_through({1.55, 0.0}), back_id);   // beyond its edge
}

TEST(SceneIntersectionTest, PosesAreSettableAndLedsAreNeverHit) {
  Scene scene;
  const int ball = scene.AddObject({"ball", Sphere{0.5}, {}, Pose({0, 0, 0}, {3, 0, 0})});
  SceneObject led;
  led.name = "led";
  led.primitive = Led{};
  led.T_WO = Pose({0, 0, 0}, {1, 0, 0});
  scene.AddObject(led);
  auto hit = scene.Intersect(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->object_id, ball);
  EXPECT_NEAR(hit->t_m, 2.5, kTolM);
  scene.SetPose("ball", Pose({0, 0, 0}, {6, 0, 0}));
  hit = scene.Intersect(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t_m, 5.5, kTolM);
  EXPECT_FALSE(scene.Intersect(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 5.0));
}

TEST(SceneIntersectionTest, RejectsBadObjects) {
  Scene scene;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  scene.AddObject({"a", Sphere{1.0}, {}, I});
  EXPECT_THROW(scene.AddObject({"a", Sphere{1.0}, {}, I}), std::invalid_argument);
  EXPECT_THROW(scene.AddObject({"", Sphere{1.0}, {}, I}), std::invalid_argument);
  EXPECT_THROW(scene.AddObject({"b", Sphere{-1.0}, {}, I}), std::invalid_argument);
  EXPECT_THROW(scene.AddObject({"c", Rectangle{{1.0, 1.0}, {{{0, 0}, {1, 0}}}, {}}, {}, I}),
               std::invalid_argument);
  EXPECT_THROW(scene.SetPose("nope", Eigen::Isometry3d::Identity()), std::invalid_argument);
  EXPECT_THROW(scene.object(7), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
