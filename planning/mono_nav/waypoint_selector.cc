#include "planning/mono_nav/waypoint_selector.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace aperture::planning {

void WaypointSelectorParams::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("waypoint selector: " + what);
  };
  require(cluster_tolerance_m > 0.0, "cluster_tolerance_m must be > 0");
  require(min_cluster_points >= 1, "min_cluster_points must be >= 1");
  require(cycle_time_s >= 0.0, "cycle_time_s must be >= 0");
  require(min_collision_threshold_m >= 0.0, "min_collision_threshold_m must be >= 0");
  require(vehicle_radius_m >= 0.0, "vehicle_radius_m must be >= 0");
  require((state_sigma_m.array() >= 0.0).all() && state_sigma_m.allFinite(),
          "state_sigma_m must be finite and >= 0");
  require(path_samples >= 2, "path_samples must be >= 2");
  require(max_height_from_goal_m >= 0.0, "max_height_from_goal_m must be >= 0 (inf: free)");
  require(max_bearing_rad > 0.0, "max_bearing_rad must be > 0 (inf: no field-of-view check)");
  require(seen_from_m >= 0.0 && std::isfinite(seen_from_m), "seen_from_m must be finite, >= 0");
}

Eigen::Vector3d Bezier3(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double tau) {
  const double s = 1.0 - tau;
  return s * s * s * p0 + 3.0 * s * s * tau * p1 + 3.0 * s * tau * tau * p2 + tau * tau * tau * p3;
}

std::vector<Eigen::Vector3d> BackProjectGrid(const cv::Mat& d_eff_m,
                                             const Eigen::Vector2d& patch_px,
                                             const perception::CameraModel& camera,
                                             const Eigen::Isometry3d& T_BC) {
  if (d_eff_m.type() != CV_32FC1) {
    throw std::invalid_argument("BackProjectGrid: the EDT map must be CV_32FC1 in metres");
  }
  std::vector<Eigen::Vector3d> points_B;
  for (int r = 0; r < d_eff_m.rows; ++r) {
    for (int c = 0; c < d_eff_m.cols; ++c) {
      const double d_eff = d_eff_m.at<float>(r, c);
      if (!(d_eff > 0.0)) continue;
      // Patch centre in pixel coordinates (pixel centres at integers).
      const Eigen::Vector2d px((c + 0.5) * patch_px.x() - 0.5, (r + 0.5) * patch_px.y() - 0.5);
      const Eigen::Vector3d bearing_C = camera.Unproject(px);
      if (!(bearing_C.z() > 1e-6)) continue;  // z-depth undefined off a forward hemisphere
      points_B.push_back(T_BC * (bearing_C * (d_eff / bearing_C.z())));
    }
  }
  return points_B;
}

WaypointSelector::WaypointSelector(const WaypointSelectorParams& params) : params_(params) {
  params_.Validate();
}

std::vector<Segment> WaypointSelector::Cluster(const std::vector<Eigen::Vector3d>& points_B) const {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(points_B.size());
  for (const Eigen::Vector3d& p : points_B) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  std::vector<pcl::PointIndices> clusters;
  if (!cloud->empty()) {
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(cloud);
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
    extraction.setClusterTolerance(params_.cluster_tolerance_m);
    extraction.setMinClusterSize(params_.min_cluster_points);
    extraction.setMaxClusterSize(static_cast<int>(points_B.size()));
    extraction.setSearchMethod(tree);
    extraction.setInputCloud(cloud);
    extraction.extract(clusters);
  }
  std::vector<Segment> segments;
  for (const pcl::PointIndices& cluster : clusters) {
    Segment segment;
    segment.points.assign(cluster.indices.begin(), cluster.indices.end());
    std::sort(segment.points.begin(), segment.points.end());
    for (int i : segment.points) segment.centroid_B += points_B[i];
    segment.centroid_B /= double(segment.points.size());
    Eigen::Vector2d variance_yz = Eigen::Vector2d::Zero();
    for (int i : segment.points) {
      variance_yz += (points_B[i] - segment.centroid_B).tail<2>().cwiseAbs2();
    }
    variance_yz /= double(segment.points.size());
    // Half the narrower extent of a uniform rectangle with the same spread (half-width = sqrt(3)
    // sigma): a tall thin trunk is narrow however tall it is.
    segment.radius_m = std::sqrt(3.0 * variance_yz.minCoeff());
    segment.distance_m = segment.centroid_B.x();
    segments.push_back(segment);
  }
  // PCL's order depends on its search structure; sort by first point for determinism.
  std::sort(segments.begin(), segments.end(),
            [](const Segment& a, const Segment& b) { return a.points.front() < b.points.front(); });
  return segments;
}

bool WaypointSelector::IsSeen(const Eigen::Vector3d& sample_B) const {
  if (!std::isfinite(params_.max_bearing_rad) || sample_B.norm() <= params_.seen_from_m) {
    return true;
  }
  // The sample's lateral extent (+- the vehicle's half width) inside the horizontal wedge.
  return sample_B.x() > 0.0 && std::atan2(std::abs(sample_B.y()) + params_.vehicle_radius_m,
                                          sample_B.x()) <= params_.max_bearing_rad;
}

bool WaypointSelector::PathIsFree(const std::vector<Eigen::Vector3d>& path_B,
                                  const std::vector<Eigen::Vector3d>& points_B) const {
  const Eigen::Vector3d half =
      params_.state_sigma_m + Eigen::Vector3d::Constant(params_.vehicle_radius_m);
  for (const Eigen::Vector3d& sample : path_B) {
    if (!IsSeen(sample)) return false;
    for (const Eigen::Vector3d& point : points_B) {
      if (((point - sample).cwiseAbs().array() <= half.array()).all()) return false;
    }
  }
  return true;
}

void WaypointSelector::ExtendTowardsGoal(const Eigen::Vector3d& goal_B,
                                         const std::vector<Eigen::Vector3d>& obstacles_B,
                                         double length_m, double standoff_m,
                                         std::vector<Eigen::Vector3d>* path_B) const {
  const Eigen::Vector3d end = path_B->back();
  const Eigen::Vector3d to_goal = goal_B - end;
  const double length = std::min(length_m, to_goal.norm());
  if (!(length > kExtensionStepM)) return;
  const Eigen::Vector3d step = to_goal.normalized() * kExtensionStepM;
  const size_t first = path_B->size();
  for (int k = 1; k * kExtensionStepM <= length; ++k) {
    const Eigen::Vector3d sample = end + k * step;
    // Only what the camera has seen ahead of the vehicle can be checked.
    if (!(sample.x() > 0.0) || !IsSeen(sample)) return;
    if (!PathIsFree({sample}, obstacles_B)) {
      while (path_B->size() > first && (sample - path_B->back()).norm() < standoff_m) {
        path_B->pop_back();
      }
      return;
    }
    path_B->push_back(sample);
  }
}

WaypointSelection WaypointSelector::Select(std::vector<Eigen::Vector3d> points_B,
                                           const Eigen::Vector3d& v_B,
                                           const Eigen::Vector3d& goal_B, WaypointOrder order,
                                           std::uint64_t seed,
                                           const std::vector<Eigen::Vector3d>* obstacles_B) const {
  if (!v_B.allFinite() || !goal_B.allFinite() || !(goal_B.norm() > 0.0)) {
    throw std::invalid_argument(
        "waypoint selector: velocity and goal must be finite and the goal "
        "must not be at the vehicle");
  }
  for (const Eigen::Vector3d& p : points_B) {
    if (!p.allFinite()) throw std::invalid_argument("waypoint selector: non-finite EDT point");
  }
  WaypointSelection selection;
  selection.points_B = std::move(points_B);
  selection.segments = Cluster(selection.points_B);

  // Cost and constraints of the binary program.
  const Eigen::Vector3d line_of_sight = goal_B.normalized();
  const double alpha =
      std::max(params_.min_collision_threshold_m, v_B.norm() * params_.cycle_time_s);
  const double eta =
      params_.vehicle_radius_m + std::max(params_.state_sigma_m.y(), params_.state_sigma_m.z());
  for (Segment& s : selection.segments) {
    s.rho_m = (s.centroid_B - s.centroid_B.dot(line_of_sight) * line_of_sight).norm();
    s.cost = s.rho_m / std::max(s.radius_m, 1e-9);
    s.meets_threshold = s.distance_m >= alpha;
    s.meets_expanse = s.radius_m >= eta;
  }

  std::vector<int> candidates;
  if (order == WaypointOrder::kOptimal) {
    for (int i = 0; i < int(selection.segments.size()); ++i) {
      const Segment& s = selection.segments[i];
      if (s.meets_threshold && s.meets_expanse) candidates.push_back(i);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      return selection.segments[a].cost < selection.segments[b].cost;
    });
  } else {
    candidates.resize(selection.segments.size());
    std::iota(candidates.begin(), candidates.end(), 0);
    std::mt19937_64 rng(seed);
    std::shuffle(candidates.begin(), candidates.end(), rng);
  }

  // Spatial windows along the Bezier path to each candidate, best first (Sec. III-D).
  // The waypoint stops short of the segment's surface by more than a window's half length in x
  // plus the cluster tolerance, so the segment's own points do not block its window.
  const double pull_back_x =
      params_.state_sigma_m.x() + params_.vehicle_radius_m + params_.cluster_tolerance_m;
  for (int i : candidates) {
    selection.tried.push_back(i);
    const Eigen::Vector3d& o = selection.segments[i].centroid_B;
    if (!(o.x() > 2.0 * pull_back_x)) continue;  // too near to approach at all
    Eigen::Vector3d waypoint = o * (1.0 - pull_back_x / o.x());
    waypoint.z() = std::clamp(waypoint.z(), goal_B.z() - params_.max_height_from_goal_m,
                              goal_B.z() + params_.max_height_from_goal_m);
    const double length = waypoint.norm();
    const Eigen::Vector3d start_tangent =
        v_B.norm() > 0.1 ? Eigen::Vector3d(v_B.normalized()) : Eigen::Vector3d(waypoint / length);
    const Eigen::Vector3d p1 = start_tangent * (length / 3.0);
    const Eigen::Vector3d p2 = waypoint * (2.0 / 3.0);
    std::vector<Eigen::Vector3d> path;
    for (int k = 0; k <= params_.path_samples; ++k) {
      path.push_back(
          Bezier3(Eigen::Vector3d::Zero(), p1, p2, waypoint, double(k) / params_.path_samples));
    }
    if (PathIsFree(path, obstacles_B != nullptr ? *obstacles_B : selection.points_B)) {
      selection.chosen = i;
      selection.waypoint_B = waypoint;
      selection.path_B = std::move(path);
      break;
    }
  }
  return selection;
}

}  // namespace aperture::planning
