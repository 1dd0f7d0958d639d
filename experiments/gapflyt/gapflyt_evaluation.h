#pragma once
// Ground-truth scoring of one GapFlyt flight (seed 002 Sec. IV: "traversal through the gap without
// collision"), shared by `aperture sim gapflyt`, `aperture bench gapflyt` and the tests.
//
// The opening: a polygon in the wall's frame O (x_O right, y_O down, z_O the wall normal pointing
// away from the start, origin at the opening's centre; the scenario's "gap" object). The crossing
// is where the body origin passes z_O = 0 going +z_O (linear interpolation between trajectory
// samples). There the vehicle's footprint in the wall plane is the body sphere (radius
// body_radius_m about B) and the four propeller disks (radius propeller_radius_m about the rotor
// centres, placed with the true attitude); the clearance is the smallest distance from any of
// them to the opening's edge (negative: it overlaps the wall).
//
//   passed = crossed inside the opening && no collision in the whole run.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "perception/camera/camera_model.h"
#include "perception/ts2p/opening_score.h"
#include "sim/scene/scene.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

struct GapflytOpening {
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector2d> polygon_O;  // (x_O, y_O) [m], >= 3 vertices, simple
  // Area centroid of the polygon [m].
  Eigen::Vector2d Centroid() const;
  // Distance from p_O to the polygon's edge, positive inside [m].
  double SignedDistance(const Eigen::Vector2d& p_O) const;
};

// The opening of the scene's object `name` (a Rectangle with one polygon or ellipse hole; an
// ellipse becomes a 64-gon). Throws std::invalid_argument when there is no such object or hole.
GapflytOpening OpeningFromScene(const sim::Scene& scene, const std::string& name = "gap");

struct GapflytCrossing {
  double t_s = 0.0;
  control::QuadState state;                       // ground truth at t_s (GroundTruthAt)
  Eigen::Vector2d p_O = Eigen::Vector2d::Zero();  // body origin in the wall plane [m]
  bool inside = false;                            // the body origin inside the polygon
  double centre_to_edge_m = 0.0;                  // SignedDistance(p_O)
  double clearance_m = 0.0;                       // footprint to the edge (see above)
  Eigen::Vector2d offset_from_centroid_m = Eigen::Vector2d::Zero();
};

struct GapflytEvaluation {
  bool passed = false;
  std::string failure_reason;  // empty when passed
  std::optional<GapflytCrossing> crossing;
};

GapflytEvaluation EvaluateGapflytFlight(const sim::SitlResult& result,
                                        const GapflytOpening& opening,
                                        const control::VehicleParameters& vehicle,
                                        const sim::CollisionParams& collision);

// The TS²P detection `opening` (CV_8UC1, reference-frame pixels) scored (perception::ScoreOpening,
// the seed's >= 75 % overlap) against the true opening projected into the camera at T_WC (the
// true pose of the detection's reference frame). Throws like ScoreOpening (e.g. the opening out
// of view).
perception::OpeningScore ScoreGapflytDetection(const cv::Mat& opening, const GapflytOpening& truth,
                                               const perception::CameraModel& camera,
                                               const Eigen::Isometry3d& T_WC);

}  // namespace aperture::experiments
