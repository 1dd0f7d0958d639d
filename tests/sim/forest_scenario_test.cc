// The `forest` scenario (seed 003): random layouts per seed that block the straight line to the
// goal in most seeds, keep every two obstacles min_gap_m apart (the passability guarantee of
// ForestParams), keep the start and the goal free, and place the full density.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

// An obstacle as the vertical cylinder the placement checked (boxes: the circumscribed one).
struct TrunkFootprint {
  Eigen::Vector2d p_W;
  double radius_m = 0.0;
};

std::vector<TrunkFootprint> Footprints(const Scenario& scenario) {
  std::vector<TrunkFootprint> out;
  for (const SceneObject& object : scenario.scene().objects()) {
    const Eigen::Vector2d p = object.T_WO.translation().head<2>();
    if (const auto* cylinder = std::get_if<Cylinder>(&object.primitive)) {
      out.push_back({p, cylinder->radius_m});
    } else if (const auto* box = std::get_if<Box>(&object.primitive)) {
      out.push_back({p, box->size_m.x() * std::sqrt(0.5)});
    }
  }
  return out;
}

Scenario Forest(int seed) {
  return BuildScenario(
      LoadScenarioParams(ScenarioConfig("forest", {}, {"seed=" + std::to_string(seed)})));
}

// Distance of p from the segment a-b.
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + s * (b - a))).norm();
}

TEST(ForestScenario, LayoutsKeepTheGapsAndTheEndsFreeButNotTheLineToTheGoal) {
  // Half the SITL vehicle's rotor-tip span (0.178 m arm + 0.0635 m propeller).
  constexpr double kVehicleRadiusM = 0.24;
  constexpr int kSeeds = 20;
  int blocked = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const Scenario scenario = Forest(seed);
    const ForestParams& f = scenario.params().forest;
    const std::vector<TrunkFootprint> obstacles = Footprints(scenario);
    ASSERT_EQ(static_cast<int>(obstacles.size()), f.trees + f.boxes) << "seed " << seed;
    const Eigen::Vector2d start = scenario.T_WB_start().translation().head<2>();
    const Eigen::Vector2d goal = f.goal_m.head<2>();
    EXPECT_GE((goal - start).norm(), 20.0);
    bool line_blocked = false;
    for (size_t i = 0; i < obstacles.size(); ++i) {
      const TrunkFootprint& a = obstacles[i];
      EXPECT_GE((a.p_W - start).norm() - a.radius_m, f.keep_out_m - 1e-9) << "seed " << seed;
      EXPECT_GE((a.p_W - goal).norm() - a.radius_m, f.keep_out_m - 1e-9) << "seed " << seed;
      for (size_t j = i + 1; j < obstacles.size(); ++j) {
        const TrunkFootprint& b = obstacles[j];
        EXPECT_GE((a.p_W - b.p_W).norm() - a.radius_m - b.radius_m, f.min_gap_m - 1e-9)
            << "seed " << seed << " obstacles " << i << ", " << j;
      }
      line_blocked |= SegmentDistance(a.p_W, start, goal) < a.radius_m + kVehicleRadiusM;
    }
    blocked += line_blocked;
  }
  // ~1.7 obstacles on the line on average (ForestParams): P(none) ~ e^-1.7 ~ 0.18, so ~16 of 20
  // seeds are blocked; fewer than 10 means the flight line is being kept free again.
  EXPECT_GE(blocked, 10) << "of " << kSeeds << " seeds";
}

TEST(ForestScenario, SeedsGiveDifferentLayoutsAndTheSameSeedTheSame) {
  const std::vector<TrunkFootprint> a = Footprints(Forest(3));
  const std::vector<TrunkFootprint> b = Footprints(Forest(3));
  const std::vector<TrunkFootprint> c = Footprints(Forest(4));
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].p_W, b[i].p_W);
  EXPECT_GT((a.front().p_W - c.front().p_W).norm(), 1e-3);
}

TEST(ForestScenario, RejectsANonPositiveGap) {
  EXPECT_THROW(LoadScenarioParams(ScenarioConfig("forest", {}, {"forest.min_gap_m=0"})),
               std::invalid_argument);
  EXPECT_THROW(LoadScenarioParams(ScenarioConfig("forest", {}, {"forest.keep_out_m=-1"})),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
