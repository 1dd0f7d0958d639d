#pragma once
// Ground-truth score of one forest flight (issue 17 acceptance): the flight succeeds when the
// vehicle came within goal_radius_m of the goal and the run had no collision. Figures: time to the
// goal (first sample within goal_radius_m), path length flown until then (or until the end), the
// least clearance between the body centre and any obstacle surface (trunks, boxes; not the
// ground), the final distance to the goal. `aperture sim forest`, `aperture bench mononav` and
// the tests all score with this function.
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "sim/scene/scene.h"

namespace aperture::experiments {

struct ForestEvaluationParams {
  double goal_radius_m = 1.0;  // the "within 1 m of the goal"
};

struct ForestEvaluation {
  bool success = false;
  bool reached_goal = false;
  bool collision = false;
  std::string failure_reason;                                        // empty on success
  double time_to_goal_s = std::numeric_limits<double>::quiet_NaN();  // NaN: not reached
  double path_length_m = 0.0;
  double min_clearance_m = std::numeric_limits<double>::infinity();  // inf: no obstacles
  std::string nearest_obstacle;  // where min_clearance_m was reached
  double final_distance_m = 0.0;
  double min_distance_m = std::numeric_limits<double>::infinity();  // to the goal
};

// Distance [m] from p_W to the solid of a cylinder, box or sphere object (0 inside); +inf for the
// other primitives (ground plane, rectangles, LEDs), which are not forest obstacles.
double DistanceToObject(const sim::SceneObject& object, const Eigen::Vector3d& p_W);

// trajectory: ground truth of the run (t = 0 first); collision: the run's collision, if any
// (its description); scene: the obstacles (every cylinder, box and sphere). Throws
// std::invalid_argument for an empty trajectory or a non-finite goal.
ForestEvaluation EvaluateForestFlight(const std::vector<control::QuadState>& trajectory,
                                      const std::optional<std::string>& collision,
                                      const Eigen::Vector3d& goal_W, const sim::Scene& scene,
                                      const ForestEvaluationParams& params = {});

}  // namespace aperture::experiments
