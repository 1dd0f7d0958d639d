#include "experiments/gap/gap_footprint.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/require.h"
#include "experiments/gap/gap_trial_evaluation.h"

namespace aperture::experiments {
namespace {

// The panel in the plane z_G = 0: |x| <= panel/2 minus |x| < opening/2 (per axis, x_G and y_G).
struct PanelRectangles {
  Eigen::Vector2d opening_half;
  Eigen::Vector2d panel_half;
};

bool InsideOpening(const PanelRectangles& r, const Eigen::Vector2d& p) {
  return (p.cwiseAbs().array() < r.opening_half.array()).all();
}

bool OnPanelRectangle(const PanelRectangles& r, const Eigen::Vector2d& p) {
  return (p.cwiseAbs().array() <= r.panel_half.array()).all();
}

// Circle (centre c, radius rho) in the plane: a point of it on the panel, if any.
std::optional<Eigen::Vector2d> CircleOnPanel(const PanelRectangles& r, const Eigen::Vector2d& c,
                                             double rho) {
  if ((c.cwiseAbs().array() + rho < r.opening_half.array()).all()) return std::nullopt;
  // Nearest point of the panel rectangle to c; the circle reaches the panel when it is within rho.
  const Eigen::Vector2d nearest = c.cwiseMax(-r.panel_half).cwiseMin(r.panel_half);
  if ((nearest - c).norm() > rho) return std::nullopt;
  // A point of the circle outside the opening and on the panel: the nearest point when c is
  // outside the opening, else the circle's point furthest out along the axis it overhangs most.
  if (!InsideOpening(r, nearest)) return nearest;
  const Eigen::Vector2d overhang = c.cwiseAbs().array() + rho - r.opening_half.array();
  const int axis = overhang.x() >= overhang.y() ? 0 : 1;
  Eigen::Vector2d p = c;
  p[axis] += std::copysign(rho, c[axis] == 0.0 ? 1.0 : c[axis]);
  return p.cwiseMax(-r.panel_half).cwiseMin(r.panel_half);
}

// Segment a-b in the plane: a point of it on the panel, if any. The opening is convex, so a
// segment with both ends inside it lies inside; else the part of it on the panel rectangle
// (Liang-Barsky clip) outside the opening.
std::optional<Eigen::Vector2d> SegmentOnPanel(const PanelRectangles& r, const Eigen::Vector2d& a,
                                              const Eigen::Vector2d& b) {
  if (InsideOpening(r, a) && InsideOpening(r, b)) return std::nullopt;
  double s0 = 0.0, s1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      // sign * (a + s d)[axis] <= panel_half[axis]
      const double p = sign * d[axis];
      const double q = r.panel_half[axis] - sign * a[axis];
      if (p == 0.0) {
        if (q < 0.0) return std::nullopt;
      } else if (p > 0.0) {
        s1 = std::min(s1, q / p);
      } else {
        s0 = std::max(s0, q / p);
      }
    }
  }
  if (s0 > s1) return std::nullopt;
  // The clipped part [s0, s1] enters or leaves the opening at most once on each side; a clipped
  // end outside the opening is on the panel, else the segment crosses the rim between them.
  for (const double s : {s0, s1}) {
    if (!InsideOpening(r, a + s * d)) return Eigen::Vector2d(a + s * d);
  }
  return std::nullopt;  // both clipped ends inside the (convex) opening: all of it is inside
}

std::string Numbered(const char* part, int i) {
  return std::string(part) + " " + std::to_string(i + 1);
}

}  // namespace

double VehicleFootprint::ReachM() const {
  double reach = body_radius_m;
  for (const Eigen::Vector3d& p : rotor_p_B) reach = std::max(reach, p.norm() + propeller_radius_m);
  return reach;
}

void VehicleFootprint::Validate() const {
  control::RequirePositive(body_radius_m, "VehicleFootprint.body_radius_m");
  control::RequirePositive(propeller_radius_m, "VehicleFootprint.propeller_radius_m");
  for (const Eigen::Vector3d& p : rotor_p_B) {
    control::Require(p.allFinite(), "VehicleFootprint.rotor_p_B", "must be finite");
  }
}

VehicleFootprint VehicleFootprintOf(const control::VehicleParameters& vehicle,
                                    const sim::CollisionParams& collision) {
  VehicleFootprint footprint;
  footprint.body_radius_m = collision.body_radius_m;
  footprint.propeller_radius_m = collision.propeller_radius_m;
  for (int i = 0; i < 4; ++i) footprint.rotor_p_B[i] = vehicle.RotorPosition_B(i);
  return footprint;
}

std::optional<FootprintContact> FootprintContactAt(const control::QuadState& state,
                                                   const GapGeometry& gap,
                                                   const VehicleFootprint& footprint,
                                                   double max_step_m) {
  const PanelRectangles panel{0.5 * gap.opening_m, 0.5 * gap.panel_m};
  const Eigen::Isometry3d T_GW = gap.T_WG.inverse();
  const Eigen::Matrix3d R_GB = T_GW.linear() * state.q_WB.toRotationMatrix();
  const Eigen::Vector3d c_G = T_GW * state.p_WB;
  const auto contact = [&](const std::string& part, const Eigen::Vector2d& p) {
    return FootprintContact{state.t_s, part, p};
  };
  // Body sphere: its section by z_G = 0 is a circle of radius sqrt(r^2 - z^2).
  const double r = footprint.body_radius_m;
  if (std::abs(c_G.z()) < r) {
    const double rho = std::sqrt(r * r - c_G.z() * c_G.z());
    if (auto p = CircleOnPanel(panel, c_G.head<2>(), rho)) return contact("body", *p);
  }
  // Propeller disks (centre c, radius R, in the plane spanned by x_B, y_B): with w the unit
  // in-disk direction along which z_G rises at slope s = |(z_G)_in-disk| and t = n x w, the
  // points c + x w + y t meet z_G = 0 at x0 = -c_z / s, a chord of half-length sqrt(R^2 - x0^2).
  const Eigen::Vector3d n_G = R_GB.col(2);
  const Eigen::Vector3d z_in_disk = Eigen::Vector3d::UnitZ() - n_G.z() * n_G;
  const double slope = z_in_disk.norm();
  const double R = footprint.propeller_radius_m;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d c = c_G + R_GB * footprint.rotor_p_B[i];
    if (slope * R < max_step_m) {
      // Nearly parallel to the panel: within one step of it, the whole disk is its section.
      if (std::abs(c.z()) <= max_step_m) {
        if (auto p = CircleOnPanel(panel, c.head<2>(), R))
          return contact(Numbered("propeller", i), *p);
      }
      continue;
    }
    const double x0 = -c.z() / slope;
    if (std::abs(x0) >= R) continue;
    const Eigen::Vector3d w = z_in_disk / slope;
    const Eigen::Vector3d t = n_G.cross(w);
    const double half = std::sqrt(R * R - x0 * x0);
    const Eigen::Vector3d mid = c + x0 * w;
    if (auto p = SegmentOnPanel(panel, (mid + half * t).head<2>(), (mid - half * t).head<2>())) {
      return contact(Numbered("propeller", i), *p);
    }
  }
  // Arms: the segment from the origin of B to rotor i meets z_G = 0 at one point.
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d end = c_G + R_GB * footprint.rotor_p_B[i];
    if ((c_G.z() < 0.0) == (end.z() < 0.0)) continue;
    const double s = c_G.z() / (c_G.z() - end.z());
    const Eigen::Vector2d p = (c_G + s * (end - c_G)).head<2>();
    if (!InsideOpening(panel, p) && OnPanelRectangle(panel, p))
      return contact(Numbered("arm", i), p);
  }
  return std::nullopt;
}

std::optional<FootprintContact> FindFootprintContact(
    const std::vector<control::QuadState>& trajectory, const GapGeometry& gap,
    const VehicleFootprint& footprint, double max_step_m) {
  footprint.Validate();
  control::RequirePositive(max_step_m, "FindFootprintContact: max_step_m");
  if (!(gap.opening_m.array() > 0.0).all() ||
      !(gap.panel_m.array() >= gap.opening_m.array()).all()) {
    throw std::invalid_argument(
        "GapGeometry: opening_m must be positive and panel_m must contain it");
  }
  const double reach = footprint.ReachM();
  const Eigen::Isometry3d T_GW = gap.T_WG.inverse();
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    const control::QuadState& b = trajectory[k];
    const double z_b = (T_GW * b.p_WB).z();
    if (k == 0) {
      if (std::abs(z_b) < reach) {
        if (auto contact = FootprintContactAt(b, gap, footprint, max_step_m)) return contact;
      }
      continue;
    }
    const control::QuadState& a = trajectory[k - 1];
    const double z_a = (T_GW * a.p_WB).z();
    // Neither pose nor the path between them comes within reach of the plane.
    if (std::min(std::abs(z_a), std::abs(z_b)) >= reach && (z_a < 0.0) == (z_b < 0.0)) continue;
    // Motion of any footprint point from a to b: translation plus reach times the rotation.
    const double motion = (b.p_WB - a.p_WB).norm() + reach * a.q_WB.angularDistance(b.q_WB);
    const int steps = std::max(1, static_cast<int>(std::ceil(motion / max_step_m)));
    for (int j = 1; j <= steps; ++j) {
      const double t_s = a.t_s + (b.t_s - a.t_s) * j / steps;
      const control::QuadState s = j == steps ? b : GroundTruthAt(trajectory, t_s);
      if (auto contact = FootprintContactAt(s, gap, footprint, max_step_m)) return contact;
    }
  }
  return std::nullopt;
}

}  // namespace aperture::experiments
