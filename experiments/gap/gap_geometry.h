#pragma once
// The gap a trial flies through, in the simulator's world (ground truth for the evaluation).
#include <Eigen/Geometry>

#include "sim/scenario/scenario.h"

namespace aperture::experiments {

struct GapGeometry {
  // True gap: origin at the opening centre, axes of planning::GapPose (x_G long side, y_G short
  // side, z_G along the traversal direction) = the scenario's "gap" object pose.
  Eigen::Isometry3d T_WG = Eigen::Isometry3d::Identity();
  Eigen::Vector2d opening_m = Eigen::Vector2d(0.8, 0.28);  // inner rectangle along x_G, y_G [m]
  // The solid panel around the opening, centred on it, in the plane z_G = 0 [m] (the scenario's
  // gap.panel_m); beyond it there is nothing to hit.
  Eigen::Vector2d panel_m = Eigen::Vector2d(1.7, 1.2);
};

// The gap of a built `gap` scenario: its "gap" object's pose, gap.opening_m and gap.panel_m.
// Throws std::out_of_range when the scene has no "gap" object.
GapGeometry GapGeometryOf(const sim::Scenario& scenario);

}  // namespace aperture::experiments
