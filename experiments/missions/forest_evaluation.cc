#include "experiments/missions/forest_evaluation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

namespace aperture::experiments {

double DistanceToObject(const sim::SceneObject& object, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p_O = object.T_WO.inverse() * p_W;
  if (const auto* cylinder = std::get_if<sim::Cylinder>(&object.primitive)) {
    // Vertical cylinder from z_O = 0 to height_m (primitives.h).
    const double radial = std::max(0.0, p_O.head<2>().norm() - cylinder->radius_m);
    const double axial = std::max({0.0, p_O.z() - cylinder->height_m, -p_O.z()});
    return std::hypot(radial, axial);
  }
  if (const auto* box = std::get_if<sim::Box>(&object.primitive)) {
    // Centred box (primitives.h): distance to the nearest point of the solid.
    return (p_O.cwiseAbs() - 0.5 * box->size_m).cwiseMax(0.0).norm();
  }
  if (const auto* sphere = std::get_if<sim::Sphere>(&object.primitive)) {
    return std::max(0.0, p_O.norm() - sphere->radius_m);
  }
  return std::numeric_limits<double>::infinity();
}

ForestEvaluation EvaluateForestFlight(const std::vector<control::QuadState>& trajectory,
                                      const std::optional<std::string>& collision,
                                      const Eigen::Vector3d& goal_W, const sim::Scene& scene,
                                      const ForestEvaluationParams& params) {
  if (trajectory.empty()) {
    throw std::invalid_argument("EvaluateForestFlight: empty trajectory (did the run start?)");
  }
  if (!goal_W.allFinite()) throw std::invalid_argument("EvaluateForestFlight: goal is not finite");
  ForestEvaluation out;
  out.collision = collision.has_value();
  for (size_t k = 0; k < trajectory.size(); ++k) {
    const control::QuadState& x = trajectory[k];
    const double distance = (x.p_WB - goal_W).norm();
    out.min_distance_m = std::min(out.min_distance_m, distance);
    if (k > 0 && !out.reached_goal) {
      out.path_length_m += (x.p_WB - trajectory[k - 1].p_WB).norm();
    }
    if (!out.reached_goal && distance <= params.goal_radius_m) {
      out.reached_goal = true;
      out.time_to_goal_s = x.t_s;
    }
    for (const sim::SceneObject& object : scene.objects()) {
      const double clearance = DistanceToObject(object, x.p_WB);
      if (clearance < out.min_clearance_m) {
        out.min_clearance_m = clearance;
        out.nearest_obstacle = object.name;
      }
    }
  }
  out.final_distance_m = (trajectory.back().p_WB - goal_W).norm();
  out.success = out.reached_goal && !out.collision;
  if (out.collision) {
    out.failure_reason = *collision;
  } else if (!out.reached_goal) {
    out.failure_reason = "did not come within the goal radius";
  }
  return out;
}

}  // namespace aperture::experiments
