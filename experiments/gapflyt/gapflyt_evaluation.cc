#include "experiments/gapflyt/gapflyt_evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <variant>

#include "experiments/gap/gap_trial_evaluation.h"
#include "planning/gapflyt/footprint_placement.h"

namespace aperture::experiments {
namespace {

constexpr int kEllipseVertices = 64;

}  // namespace

Eigen::Vector2d GapflytOpening::Centroid() const {
  double area2 = 0.0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < polygon_O.size(); ++i) {
    const Eigen::Vector2d& a = polygon_O[i];
    const Eigen::Vector2d& b = polygon_O[(i + 1) % polygon_O.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    area2 += cross;
    sum += cross * (a + b);
  }
  return sum / (3.0 * area2);
}

double GapflytOpening::SignedDistance(const Eigen::Vector2d& p) const {
  return planning::PolygonSignedDistance(polygon_O, p);
}

GapflytOpening OpeningFromScene(const sim::Scene& scene, const std::string& name) {
  const sim::SceneObject& object = scene.object(name);  // throws for an unknown name
  const auto* wall = std::get_if<sim::Rectangle>(&object.primitive);
  GapflytOpening opening;
  opening.T_WO = object.T_WO;
  if (wall && !wall->polygon_holes.empty()) {
    opening.polygon_O = wall->polygon_holes.front();
  } else if (wall && !wall->ellipse_holes.empty()) {
    const sim::EllipseHole& e = wall->ellipse_holes.front();
    const Eigen::Rotation2Dd R(e.angle_rad);
    for (int k = 0; k < kEllipseVertices; ++k) {
      const double phi = 2.0 * M_PI * k / kEllipseVertices;
      opening.polygon_O.push_back(e.center_m +
                                  R * Eigen::Vector2d(e.semi_axes_m.x() * std::cos(phi),
                                                      e.semi_axes_m.y() * std::sin(phi)));
    }
  } else {
    throw std::invalid_argument("OpeningFromScene: object '" + name +
                                "' is not a wall with an opening (a Rectangle with a polygon or "
                                "ellipse hole); use the gapflyt scenario");
  }
  return opening;
}

GapflytEvaluation EvaluateGapflytFlight(const sim::SitlResult& result,
                                        const GapflytOpening& opening,
                                        const control::VehicleParameters& vehicle,
                                        const sim::CollisionParams& collision) {
  GapflytEvaluation evaluation;
  const Eigen::Isometry3d T_OW = opening.T_WO.inverse();
  const std::vector<control::QuadState>& trajectory = result.trajectory;
  for (std::size_t k = 1; k < trajectory.size(); ++k) {
    const double z0 = (T_OW * trajectory[k - 1].p_WB).z();
    const double z1 = (T_OW * trajectory[k].p_WB).z();
    if (!(z0 < 0.0 && z1 >= 0.0)) continue;
    const double s = z1 == z0 ? 1.0 : -z0 / (z1 - z0);
    GapflytCrossing crossing;
    crossing.t_s = trajectory[k - 1].t_s + s * (trajectory[k].t_s - trajectory[k - 1].t_s);
    crossing.state = GroundTruthAt(trajectory, crossing.t_s);
    crossing.p_O = (T_OW * crossing.state.p_WB).head<2>();
    crossing.centre_to_edge_m = opening.SignedDistance(crossing.p_O);
    crossing.inside = crossing.centre_to_edge_m > 0.0;
    crossing.offset_from_centroid_m = crossing.p_O - opening.Centroid();
    // Footprint: the body sphere and the propeller disks, projected along z_O.
    double clearance = crossing.centre_to_edge_m - collision.body_radius_m;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d rotor_W =
          crossing.state.p_WB + crossing.state.q_WB * vehicle.RotorPosition_B(i);
      const Eigen::Vector2d rotor_O = (T_OW * rotor_W).head<2>();
      clearance =
          std::min(clearance, opening.SignedDistance(rotor_O) - collision.propeller_radius_m);
    }
    crossing.clearance_m = clearance;
    evaluation.crossing = crossing;
    break;  // the first crossing is the traversal
  }
  if (result.collision) {
    evaluation.failure_reason = "collision with '" + result.collision->object_name + "'";
  } else if (!evaluation.crossing) {
    evaluation.failure_reason = "did not cross the wall plane";
  } else if (!evaluation.crossing->inside) {
    evaluation.failure_reason = "crossed the wall plane outside the opening";
  }
  evaluation.passed = evaluation.failure_reason.empty();
  return evaluation;
}

perception::OpeningScore ScoreGapflytDetection(const cv::Mat& opening, const GapflytOpening& truth,
                                               const perception::CameraModel& camera,
                                               const Eigen::Isometry3d& T_WC) {
  const Eigen::Isometry3d T_CO = T_WC.inverse() * truth.T_WO;
  std::vector<cv::Point> polygon_px;
  for (const Eigen::Vector2d& v : truth.polygon_O) {
    Eigen::Vector2d px;
    const Eigen::Vector3d p_C = T_CO * Eigen::Vector3d(v.x(), v.y(), 0.0);
    if (!(p_C.z() > 0.0) || !camera.Project(p_C, &px)) {
      throw std::invalid_argument(
          "ScoreGapflytDetection: a corner of the true opening is behind or outside the camera "
          "model; score detections whose reference frame sees the opening");
    }
    polygon_px.emplace_back(static_cast<int>(std::lround(px.x())),
                            static_cast<int>(std::lround(px.y())));
  }
  cv::Mat mask = cv::Mat::zeros(opening.size(), CV_8UC1);
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{polygon_px}, cv::Scalar(255));
  return perception::ScoreOpening(opening, mask);
}

}  // namespace aperture::experiments
