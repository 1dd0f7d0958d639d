#pragma once
// Waypoint selection over the ego-dynamic depth map (seed 003 Sec. III-C, III-D):
//  1. every patch of the EDT map is back-projected to a point in the body frame B (x forward =
//     the line of sight, y-z the field-of-view plane of Fig. 4) at its effective distance d_eff;
//  2. the points are clustered into segments S_i with PCL's Euclidean clustering; each has a
//     centroid o_i, a radius r_i (sqrt(3) times the smaller of its standard deviations along y and
//     z: the half-width of a uniform rectangle with that spread, so a tall thin trunk counts as
//     narrow) and d_i = o_i.x;
//  3. the cost C_i = rho_i / r_i, rho_i the distance of o_i from the line of sight to the goal:
//     near the line of sight and wide (the paper's "nearest and maximum size free space");
//  4. the binary program  min C^T kappa  s.t.  sum kappa = 1 (one-hot),
//        d_i kappa_i >= alpha kappa_i,  alpha = v_t t_t      (collision threshold, (8))
//        r_i kappa_i >= eta kappa_i,    eta = delta + max(sigma_y, sigma_z)   (expanse, (9))
//     is solved exactly: a feasible kappa is a unit vector e_i of a segment meeting both
//     constraints, so the optimum is the feasible segment of least cost (ties: lower index);
//  5. a cubic Bezier path from the vehicle (tangent to its velocity) to the waypoint (o_i pulled
//     back along its ray by the window half length in x plus the cluster tolerance) is checked with
//     spatial
//     windows (Sec. III-D): boxes of half size sigma + delta around samples of the path must hold
//     no EDT point; a path that fails marks its segment non-traversable and the next best is
//     tried (the count of such rejections is the "replanning" of Table II).
//     Beyond the paper, a path must also run through seen space (IsSeen: within the camera's
//     horizontal field of view), and ExtendTowardsGoal continues a chosen path towards the goal.
// Frames: B body (x forward, y left, z up), C camera (OpenCV), T_BC the camera mount. Units SI.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::planning {

struct WaypointSelectorParams {
  // PCL Euclidean cluster tolerance [m] in EDT space, where d_eff compresses depth (40 m -> ~6 m
  // with the default EgoDynamicParams), so one tolerance serves near and far patches.
  double cluster_tolerance_m = 0.35;
  int min_cluster_points = 4;
  // t_t of the collision threshold alpha = v_t t_t [s] (computation + response time).
  double cycle_time_s = 0.3;
  // Minimum alpha [m]: even at rest a segment closer than this is an obstacle.
  double min_collision_threshold_m = 0.5;
  // delta: half the vehicle's width [m] (rotor tip to centre, 0.25 m for a 450-class frame).
  double vehicle_radius_m = 0.25;
  // sigma_x, sigma_y, sigma_z: state-estimation standard deviations [m] (paper Table III).
  Eigen::Vector3d state_sigma_m = Eigen::Vector3d(0.1, 0.1, 0.1);
  int path_samples = 24;  // spatial windows along the Bezier path
  // The waypoint's z is clamped to goal_B.z +- this [m] (beyond the paper; inf = its free 3-D
  // waypoint). With points in a gravity-aligned frame it keeps the flight near the goal's height
  // instead of climbing towards the sky, whose far patches dominate the largest free segments.
  double max_height_from_goal_m = std::numeric_limits<double>::infinity();
  // Seen space (beyond the paper): beyond seen_from_m of the vehicle a path sample, widened by
  // vehicle_radius_m to each side, must lie within +-max_bearing_rad of x (the camera's
  // horizontal field of view, which ForestMission sets from its camera): the map holds only what
  // the camera saw, and a window beside the field of view is "free" only because nothing there
  // was seen. Nearer samples are where the vehicle is and just was. inf: no check.
  double max_bearing_rad = std::numeric_limits<double>::infinity();
  double seen_from_m = 1.0;

  void Validate() const;  // std::invalid_argument naming the field
};

struct Segment {
  Eigen::Vector3d centroid_B = Eigen::Vector3d::Zero();  // o_i
  double radius_m = 0.0;                                 // r_i
  double distance_m = 0.0;                               // d_i = o_i.x
  double rho_m = 0.0;  // distance of o_i from the line of sight to the goal
  double cost = 0.0;   // C_i
  bool meets_threshold = false;
  bool meets_expanse = false;
  std::vector<int> points;  // indices into WaypointSelection::points_B
};

struct WaypointSelection {
  std::vector<Eigen::Vector3d> points_B;  // back-projected EDT map (one per patch with d_eff > 0)
  std::vector<Segment> segments;
  std::vector<int> tried;     // segments whose paths were checked, in order
  std::optional<int> chosen;  // index into segments; nullopt: no traversable segment
  Eigen::Vector3d waypoint_B = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> path_B;  // sampled Bezier path of the chosen segment
  int Replans() const { return chosen ? int(tried.size()) - 1 : int(tried.size()); }
};

// Cubic Bezier q(tau) = sum_i C(3,i) tau^i (1-tau)^(3-i) p_i (Sec. III-D (14)).
Eigen::Vector3d Bezier3(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double tau);

// Back-projects a patch grid of effective distances (CV_32FC1 rows x cols, z-depth along the
// optical axis) through `camera` at the patch centres (patch size `patch_px` in the camera's
// pixels) into B; patches with d_eff <= 0 are left out (imminent collisions, kept in the map).
std::vector<Eigen::Vector3d> BackProjectGrid(const cv::Mat& d_eff_m,
                                             const Eigen::Vector2d& patch_px,
                                             const perception::CameraModel& camera,
                                             const Eigen::Isometry3d& T_BC);

enum class WaypointOrder { kOptimal, kRandom };

class WaypointSelector {
 public:
  explicit WaypointSelector(const WaypointSelectorParams& params = {});

  // points_B: the back-projected EDT map; v_B: the vehicle's velocity in B [m/s]; goal_B: the
  // goal in B (its direction is the line of sight of rho_i). kOptimal tries the feasible segments
  // by increasing cost; kRandom (Table II's baseline) tries all segments in a random order drawn
  // from `seed`. obstacles_B: what the spatial windows check the paths against, when not
  // points_B — the metric obstacle points (depth, not d_eff) the path will actually fly past; the
  // EDT map compresses distances and lateral gaps with them, but not the vehicle. Throws
  // std::invalid_argument on non-finite inputs.
  WaypointSelection Select(std::vector<Eigen::Vector3d> points_B, const Eigen::Vector3d& v_B,
                           const Eigen::Vector3d& goal_B,
                           WaypointOrder order = WaypointOrder::kOptimal, std::uint64_t seed = 0,
                           const std::vector<Eigen::Vector3d>* obstacles_B = nullptr) const;

  // True when `sample` lies in seen space (max_bearing_rad, seen_from_m).
  bool IsSeen(const Eigen::Vector3d& sample_B) const;

  // Spatial-window check of one path: false when a window around a sample holds a point or a
  // sample is not in seen space (IsSeen).
  bool PathIsFree(const std::vector<Eigen::Vector3d>& path_B,
                  const std::vector<Eigen::Vector3d>& points_B) const;

  // Beyond the paper: appends samples (kExtensionStepM apart) from path_B's end towards goal_B,
  // up to length_m, while they lie ahead (x > 0) in seen space and their windows hold none of
  // obstacles_B. When an obstacle's window stops it, the samples within standoff_m of the
  // blocked one are dropped again: a path that ends at rest facing an obstacle leaves too little
  // room for any path around it.
  void ExtendTowardsGoal(const Eigen::Vector3d& goal_B,
                         const std::vector<Eigen::Vector3d>& obstacles_B, double length_m,
                         double standoff_m, std::vector<Eigen::Vector3d>* path_B) const;
  static constexpr double kExtensionStepM = 0.2;  // < the windows' 0.35 m half size: no gaps

  const WaypointSelectorParams& params() const { return params_; }

 private:
  std::vector<Segment> Cluster(const std::vector<Eigen::Vector3d>& points_B) const;

  WaypointSelectorParams params_;
};

}  // namespace aperture::planning
