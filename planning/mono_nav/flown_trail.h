#pragma once
// The path a vehicle has flown, kept as points spacing_m apart (latest last): space it can fly
// back along without a map, because it was just there. ForestMission backs off along it when it
// stalls in front of an obstacle its depth model puts too close (beyond seed 003, which has no
// recovery). Frame W (the odometry frame), metres.
#include <Eigen/Core>
#include <vector>

namespace aperture::planning {

class FlownTrail {
 public:
  // Throws std::invalid_argument unless spacing_m > 0.
  explicit FlownTrail(double spacing_m);

  // Appends p_W when it lies spacing_m or more from the latest point (always the first one).
  void Add(const Eigen::Vector3d& p_W);

  // The path from p_W back along the trail, latest point first, ending at the first point where
  // its length reaches length_m (or at the trail's first point); {p_W} on an empty trail.
  std::vector<Eigen::Vector3d> BackOffPath(const Eigen::Vector3d& p_W, double length_m) const;

  // After flying path_W = BackOffPath(...): drops the trail points it flew back over, keeping
  // its end (where the vehicle now is) as the latest point.
  void Retrace(const std::vector<Eigen::Vector3d>& path_W);

  const std::vector<Eigen::Vector3d>& points_W() const { return points_W_; }

 private:
  double spacing_m_;
  std::vector<Eigen::Vector3d> points_W_;
};

// Length of the polyline through points_W [m].
double PolylineLength(const std::vector<Eigen::Vector3d>& points_W);

}  // namespace aperture::planning
