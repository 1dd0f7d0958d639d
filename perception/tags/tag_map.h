#pragma once
// Tag map (Faessler thesis, paper D, Sec. D.4): "to build a metrically consistent map, we run a
// pose-graph optimization over all detected tags of all images", here with Ceres instead of iSAM.
//
// Graph: one pose T_WT per tag (family, id) and one pose T_WC per image; each tag observation
// T_CT (with its 6x6 covariance from TagPoseEstimator) is an edge with the residual
//   r = L [ p_CT(pred) - p_CT(meas) ; Log(R_CT(pred) R_CT(meas)^T) ],  T_CT(pred) = T_WC^-1 T_WT,
// L^T L = (Sigma_meas + floor)^-1 (the rotation part in C, matching the covariance's left
// perturbation), under a Huber loss; the origin tag's pose is fixed (the gauge: paper D's origin
// tag "provides a common reference frame for both robots").
// Gravity (paper D: each image is sent "together with the onboard pose estimate of the
// quadrotor"): an image may carry the direction of gravity in C from the vehicle's attitude
// estimate; its edge r = (R_WC down_C - down_W) / sigma_gravity ties the camera's roll and pitch
// to W (gravity-aligned, z up). Without it the map's tilt about the origin tag is observable only
// through the origin tag's own rotation measurements (~1 deg each for a 0.25 m tag at 2.5 m), and
// a tilt of a fraction of a degree moves tags 6 m away by centimetres.
// Odometry (the same onboard estimate's position and heading): an image may carry its camera pose
// T_OC in the vehicle's odometry frame O (drifting, so only differences are used). Consecutive
// images that both carry one are joined by the relative-pose edge
//   r = L [ p_AB(pred) - p_AB(meas) ; Log(R_AB(pred) R_AB(meas)^T) ],  T_AB(meas) = T_OA^-1 T_OB,
// (A, B: the earlier and later camera) whose covariance grows like a random walk with the path
// flown between them, s: sigma_p^2 = floor_p^2 + q_p^2 s per axis, sigma_R^2 = floor_R^2 + q_R^2 s.
// These tie the cameras' headings and positions between the images that see the origin tag and
// the rest, which tag observations alone do only through chains of jointly seen tags.
// Incremental: an image joins the graph once it sees a tag already in the map (its camera pose is
// initialised from the most certain such tag, its new tags from the camera: the "before
// optimization" map) or, with odometry, once the image before or after it is in the graph (its
// pose chained through the odometry); images that do not (yet) connect wait. Every solve_every
// images the graph is re-solved from the current estimate; Optimize() solves to convergence, drops
// observations whose whitened error exceeds outlier_chi2 (flipped poses the resolver missed) and
// re-solves, then computes the tags' marginal covariances.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "perception/led/led_pose_refiner.h"

namespace ceres {
class Problem;
namespace internal {
class ResidualBlock;
}  // namespace internal
}  // namespace ceres

namespace aperture::perception {

struct TagMapParams {
  int origin_id = 0;  // the gauge tag (any family)
  // Pose of the origin tag in W. Default: lying on the ground at the origin, x_T = x_W and z_T
  // pointing down into the ground (the `tags` scenario's origin tag), so W has z up.
  Eigen::Vector3d origin_p_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d origin_rpy_deg = Eigen::Vector3d(180.0, 0.0, 0.0);
  // Added to every observation covariance: model errors the corner noise does not explain
  // (calibration, tag flatness) [m], [rad].
  double floor_sigma_m = 0.002;
  double floor_sigma_rad = 0.005;
  // sigma of a per-image gravity direction (the vehicle's roll/pitch estimate) [deg].
  double gravity_sigma_deg = 1.0;
  // Odometry drift as a random walk over the path flown (see above): 0.03 m/sqrt(m) is 10 cm
  // after 10 m (1 %, a VIO's usual drift), 0.3 deg/sqrt(m) about 1 deg after 10 m; the floors keep
  // the edge of a hovering vehicle finite [m], [deg].
  double odometry_sigma_m_per_sqrt_m = 0.03;
  double odometry_sigma_deg_per_sqrt_m = 0.3;
  double odometry_floor_sigma_m = 0.001;
  double odometry_floor_sigma_deg = 0.05;
  double huber_scale = 2.0;     // on the whitened residual norm (in sigmas)
  double outlier_chi2 = 22.46;  // chi^2, 6 DOF, 99.9 %: larger whitened errors are dropped
  int solve_every = 10;         // images between incremental solves (0: only in Optimize)
  int incremental_iterations = 5;
  int max_iterations = 100;
  std::size_t max_pending_images = 1000;  // unconnected images kept for later (oldest dropped)

  // std::invalid_argument naming the field for non-positive sigmas, scales or counts.
  void Validate() const;
  Eigen::Isometry3d T_W_origin() const;
};

// One tag seen in one image.
struct TagMapObservation {
  std::string family;
  int id = -1;
  double tag_size_m = 0.0;
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Identity();  // [p_CT; rotation in C]
};

// What the vehicle's onboard estimate says about an image (paper D: images are sent "together
// with the onboard pose estimate of the quadrotor"); either part may be missing.
struct TagMapOnboardEstimate {
  // Direction of gravity (down) in C from the attitude estimate (any length > 0).
  std::optional<Eigen::Vector3d> down_C;
  // Camera pose in the odometry frame O (p_O = T_OC * p_C); O drifts, only differences are used.
  std::optional<Eigen::Isometry3d> T_OC;
};

struct MappedTag {
  std::string family;
  int id = -1;
  double size_m = 0.0;
  Eigen::Isometry3d T_WT = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_WT_initial = Eigen::Isometry3d::Identity();  // before optimization
  // Marginal covariance of [p_WT [m]; rotation [rad], left perturbation in W]; zero for the
  // origin (fixed) and before Optimize().
  Matrix6d covariance = Matrix6d::Zero();
  bool has_covariance = false;
  int observations = 0;  // inliers in the graph
  int rejected = 0;      // dropped as outliers
};

struct TagMapSolveSummary {
  bool converged = false;
  bool covariance_ok = false;
  int iterations = 0;
  int rounds = 0;  // solve + outlier rejection rounds
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int rejected_observations = 0;
  double solve_time_s = 0.0;
};
std::ostream& operator<<(std::ostream& os, const TagMapSolveSummary& summary);

class TagMap {
 public:
  explicit TagMap(const TagMapParams& params = {});
  ~TagMap();
  TagMap(const TagMap&) = delete;
  TagMap& operator=(const TagMap&) = delete;

  // The tags seen in one image and what the onboard estimate says about it. Images come in
  // flight order (odometry joins consecutive ones; an image without tags only adds its odometry
  // to the path length). std::invalid_argument for a non-positive size, a non-finite pose, a
  // covariance that is not symmetric positive definite, a zero or non-finite down_C or a
  // non-finite T_OC.
  void AddImage(double t_s, const std::vector<TagMapObservation>& observations,
                const TagMapOnboardEstimate& onboard = {});

  // Solves to convergence with outlier rejection, then the marginal covariances.
  TagMapSolveSummary Optimize();

  std::vector<MappedTag> Tags() const;  // sorted by (family, id)
  int images_in_graph() const { return static_cast<int>(cameras_.size()); }
  int odometry_edges() const { return odometry_edges_; }
  int pending_images() const { return static_cast<int>(pending_.size()); }
  const TagMapParams& params() const { return params_; }

 private:
  using Key = std::pair<std::string, int>;
  using PoseBlock = std::array<double, 7>;  // qx qy qz qw px py pz (T_W*)
  struct Image {
    int sequence;  // index among the images with tags, in flight order
    double t_s;
    std::vector<TagMapObservation> observations;
    std::optional<Eigen::Vector3d> down_C;  // unit
    std::optional<Eigen::Isometry3d> T_OC;
    double path_m;  // odometry path length flown since the first image
  };
  struct Camera {
    double* pose;  // block in cameras_
    std::optional<Eigen::Isometry3d> T_OC;
    double path_m;
  };
  struct Edge {
    ceres::internal::ResidualBlock* block;  // ceres::ResidualBlockId
    Key tag;
  };
  struct TagState {
    PoseBlock pose;
    Eigen::Isometry3d T_WT_initial;
    std::string family;
    double size_m;
    Matrix6d covariance = Matrix6d::Zero();
    bool has_covariance = false;
    int rejected = 0;
  };
  std::optional<Eigen::Isometry3d> InitialCameraPose(const Image& image) const;
  bool TryInsert(const Image& image);
  void AddOdometryEdge(const Camera& earlier, const Camera& later);
  void InsertPending();
  void Solve(int max_iterations, TagMapSolveSummary* summary);
  int RejectOutliers();
  bool ComputeCovariances();

  TagMapParams params_;
  std::unique_ptr<ceres::Problem> problem_;
  std::map<Key, TagState> tags_;  // node addresses are stable: Ceres holds pointers into them
  std::deque<PoseBlock> cameras_;
  std::map<int, Camera> camera_of_sequence_;  // images in the graph by Image::sequence
  int odometry_edges_ = 0;
  int next_sequence_ = 0;
  std::optional<Eigen::Vector3d> last_p_OC_;  // of the last image with odometry (path length)
  double path_m_ = 0.0;
  std::vector<Edge> edges_;
  std::deque<Image> pending_;
  int images_since_solve_ = 0;
};

}  // namespace aperture::perception
