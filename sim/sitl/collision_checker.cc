#include "sim/sitl/collision_checker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "control/require.h"

namespace aperture::sim {
void CollisionParams::Validate() const {
  control::RequirePositive(body_radius_m, "CollisionParams.body_radius_m");
  control::RequirePositive(propeller_radius_m, "CollisionParams.propeller_radius_m");
  control::RequirePositive(max_touchdown_speed_mps, "CollisionParams.max_touchdown_speed_mps");
  control::RequirePositive(max_touchdown_tilt_rad, "CollisionParams.max_touchdown_tilt_rad");
  if (sphere_rays < 6) {
    throw std::invalid_argument("CollisionParams.sphere_rays = " + std::to_string(sphere_rays) +
                                " must be >= 6 (64 recommended)");
  }
  if (disk_rays < 6) {
    throw std::invalid_argument("CollisionParams.disk_rays = " + std::to_string(disk_rays) +
                                " must be >= 6 (12 recommended)");
  }
}

void CollisionChecker::Validate(const QuadrotorDynamicsParams& dynamics,
                                const CollisionParams& params) {
  params.Validate();
  dynamics.Validate();
  if (dynamics.ground_contact_enabled && params.ground_enabled &&
      !(dynamics.landing_gear_height_m > params.body_radius_m)) {
    throw std::invalid_argument(
        "QuadrotorDynamicsParams.landing_gear_height_m = " +
        std::to_string(dynamics.landing_gear_height_m) +
        " must exceed CollisionParams.body_radius_m = " + std::to_string(params.body_radius_m) +
        " with ground contact on: resting on the gear would put the body into the ground");
  }
}

CollisionChecker::CollisionChecker(const QuadrotorDynamicsParams& dynamics,
                                   const CollisionParams& params)
    : params_(params), ground_height_m_(dynamics.ground_height_m) {
  Validate(dynamics, params_);
  const control::VehicleParameters& vehicle = dynamics.vehicle;
  reach_m_ = params_.body_radius_m;
  for (int i = 0; i < 4; ++i) {
    rotor_positions_B_.push_back(vehicle.RotorPosition_B(i));
    reach_m_ = std::max(reach_m_, rotor_positions_B_.back().norm() + params_.propeller_radius_m);
  }
  // Fibonacci sphere: near-uniform directions, the golden-angle spiral in z.
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < params_.sphere_rays; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / params_.sphere_rays;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = golden_angle * i;
    sphere_directions_.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  for (int i = 0; i < params_.disk_rays; ++i) {
    const double phi = 2.0 * M_PI * i / params_.disk_rays;
    disk_directions_B_.emplace_back(std::cos(phi), std::sin(phi), 0.0);
  }
}

std::optional<Collision> CollisionChecker::Check(const Scene* scene,
                                                 const control::QuadState& state,
                                                 const Eigen::Vector3d& previous_p_WB) const {
  const Eigen::Matrix3d R_WB = state.q_WB.toRotationMatrix();
  const Eigen::Vector3d& p = state.p_WB;
  if (params_.ground_enabled) {
    const double h = ground_height_m_;
    if (p.z() - params_.body_radius_m <= h) {
      return Collision{"ground", "body", Eigen::Vector3d(p.x(), p.y(), h)};
    }
    // Lowest point of a disk with unit normal n: c - R (z_W - n_z n) / |z_W - n_z n|.
    const Eigen::Vector3d n_W = R_WB.col(2);
    Eigen::Vector3d down_in_plane = -(Eigen::Vector3d::UnitZ() - n_W.z() * n_W);
    const double in_plane_norm = down_in_plane.norm();
    if (in_plane_norm > 1e-12) down_in_plane /= in_plane_norm;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d lowest_W =
          p + R_WB * rotor_positions_B_[i] + params_.propeller_radius_m * down_in_plane;
      if (lowest_W.z() <= h) {
        return Collision{"ground", "propeller " + std::to_string(i + 1),
                         Eigen::Vector3d(lowest_W.x(), lowest_W.y(), h)};
      }
    }
  }
  if (scene == nullptr || scene->objects().empty()) return std::nullopt;

  // Broad phase: every ray below lies within reach_m_ of the segment previous_p_WB -> p, so an
  // object whose bounding sphere is farther than that cannot be hit (nor an ignored one, nor an
  // LED: IntersectPrimitive never hits those).
  struct Candidate {
    const SceneObject* object;
    Eigen::Isometry3d T_OW;
  };
  std::vector<Candidate> candidates;
  const Eigen::Vector3d sweep_W = p - previous_p_WB;
  for (const SceneObject& object : scene->objects()) {
    if (std::holds_alternative<Led>(object.primitive) ||
        std::find(params_.ignored_objects.begin(), params_.ignored_objects.end(), object.name) !=
            params_.ignored_objects.end()) {
      continue;
    }
    const double radius_m = BoundingRadius(object.primitive);
    if (std::isfinite(radius_m)) {
      const Eigen::Vector3d c_W = object.T_WO * BoundingCenter(object.primitive);
      const double s =
          sweep_W.squaredNorm() > 0.0
              ? std::clamp((c_W - previous_p_WB).dot(sweep_W) / sweep_W.squaredNorm(), 0.0, 1.0)
              : 1.0;
      if ((c_W - (previous_p_WB + s * sweep_W)).norm() > radius_m + reach_m_) continue;
    }
    candidates.push_back({&object, object.T_WO.inverse()});
  }
  if (candidates.empty()) return std::nullopt;

  std::optional<Collision> nearest;
  double nearest_fraction = std::numeric_limits<double>::infinity();
  // Keeps the hit reached after the smallest fraction of its ray's length; the part's name is
  // built for a new nearest hit only.
  const auto cast = [&](const Eigen::Vector3d& o_W, const Eigen::Vector3d& d_W, double length_m,
                        const char* part, int index) {
    const Eigen::Vector3d d = d_W.normalized();
    double best_t = length_m;
    const SceneObject* hit_object = nullptr;
    for (const Candidate& candidate : candidates) {
      LocalHit local;
      if (IntersectPrimitive(candidate.object->primitive, candidate.T_OW * o_W,
                             candidate.T_OW.linear() * d, 0.0, best_t, &local)) {
        best_t = local.t_m;
        hit_object = candidate.object;
      }
    }
    if (hit_object == nullptr) return;
    const double fraction = best_t / length_m;
    if (fraction < nearest_fraction) {
      nearest_fraction = fraction;
      nearest = Collision{hit_object->name,
                          index > 0 ? std::string(part) + " " + std::to_string(index) : part,
                          o_W + best_t * d};
    }
  };
  if (sweep_W.norm() > 1e-9) cast(previous_p_WB, sweep_W, sweep_W.norm(), "sweep", 0);
  if (nearest) return nearest;
  for (const Eigen::Vector3d& d : sphere_directions_) cast(p, d, params_.body_radius_m, "body", 0);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d arm_W = R_WB * rotor_positions_B_[i];
    cast(p, arm_W, arm_W.norm(), "arm", i + 1);
    for (const Eigen::Vector3d& d_B : disk_directions_B_) {
      cast(p + arm_W, R_WB * d_B, params_.propeller_radius_m, "propeller", i + 1);
    }
  }
  return nearest;
}

std::optional<Collision> CollisionChecker::CheckTouchdown(const Eigen::Vector3d& p_WB,
                                                          double speed_mps, double tilt_rad) const {
  if (!params_.ground_enabled || (speed_mps <= params_.max_touchdown_speed_mps &&
                                  tilt_rad <= params_.max_touchdown_tilt_rad)) {
    return std::nullopt;
  }
  return Collision{"ground", "landing gear", Eigen::Vector3d(p_WB.x(), p_WB.y(), ground_height_m_)};
}

}  // namespace aperture::sim
