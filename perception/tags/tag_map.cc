#include "perception/tags/tag_map.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace aperture::perception {
namespace {

using SeManifold =
    ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>;

template <typename Block>
Eigen::Isometry3d ToIsometry(const Block& block) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(block[3], block[0], block[1], block[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(block[4], block[5], block[6]);
  return T;
}

std::array<double, 7> ToBlock(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.rotation());
  const Eigen::Vector3d& p = T.translation();
  return {q.x(), q.y(), q.z(), q.w(), p.x(), p.y(), p.z()};
}

// The edge between two poses T_WA, T_WB with the measurement T_AB (see the header): a tag
// observation (A = C, B = T) or odometry between two images (A, B = the earlier and later C).
struct RelativePoseResidual {
  RelativePoseResidual(const Eigen::Isometry3d& T_AB, const Matrix6d& sqrt_information)
      : q_AB_measured(T_AB.rotation()),
        p_AB_measured(T_AB.translation()),
        sqrt_information(sqrt_information) {}

  template <typename S>
  bool operator()(const S* pose_A, const S* pose_B, S* residual) const {
    using Quaternion = Eigen::Quaternion<S>;
    using Vector3 = Eigen::Matrix<S, 3, 1>;
    const Eigen::Map<const Quaternion> q_WA(pose_A);
    const Eigen::Map<const Vector3> p_WA(pose_A + 4);
    const Eigen::Map<const Quaternion> q_WB(pose_B);
    const Eigen::Map<const Vector3> p_WB(pose_B + 4);
    const Quaternion q_AW = q_WA.conjugate();
    const Vector3 p_AB = q_AW * (p_WB - p_WA);
    Quaternion q_error = (q_AW * q_WB) * q_AB_measured.conjugate().template cast<S>();
    if (q_error.w() < S(0)) q_error.coeffs() = -q_error.coeffs();
    Eigen::Matrix<S, 6, 1> error;
    error.template head<3>() = p_AB - p_AB_measured.template cast<S>();
    error.template tail<3>() = S(2) * q_error.vec();  // Log for small errors
    Eigen::Map<Eigen::Matrix<S, 6, 1>> whitened(residual);
    whitened = sqrt_information.template cast<S>() * error;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Isometry3d& T_AB, const Matrix6d& covariance) {
    // L with L^T L = Sigma^-1: the inverse of Sigma's Cholesky factor ((L^-1)^T L^-1 = Sigma^-1).
    const Matrix6d sqrt_information =
        Eigen::LLT<Matrix6d>(covariance).matrixL().solve(Matrix6d::Identity());
    return new ceres::AutoDiffCostFunction<RelativePoseResidual, 6, 7, 7>(
        new RelativePoseResidual(T_AB, sqrt_information));
  }

  Eigen::Quaterniond q_AB_measured;
  Eigen::Vector3d p_AB_measured;
  Matrix6d sqrt_information;
};

Matrix6d DiagonalCovariance(double sigma_p, double sigma_rad) {
  return (Eigen::Matrix<double, 6, 1>() << Eigen::Vector3d::Constant(sigma_p),
          Eigen::Vector3d::Constant(sigma_rad))
      .finished()
      .cwiseAbs2()
      .asDiagonal();
}

// The gravity edge of one image (see the header); parameter: the T_WC block.
struct GravityResidual {
  GravityResidual(const Eigen::Vector3d& down_C, double sigma_rad)
      : down_C(down_C), inverse_sigma(1.0 / sigma_rad) {}

  template <typename S>
  bool operator()(const S* camera, S* residual) const {
    const Eigen::Map<const Eigen::Quaternion<S>> q_WC(camera);
    const Eigen::Matrix<S, 3, 1> down_W = q_WC * down_C.cast<S>();
    residual[0] = S(inverse_sigma) * down_W.x();
    residual[1] = S(inverse_sigma) * down_W.y();
    residual[2] = S(inverse_sigma) * (down_W.z() + S(1));  // second order in the tilt
    return true;
  }

  Eigen::Vector3d down_C;
  double inverse_sigma;
};

}  // namespace

void TagMapParams::Validate() const {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument("apriltag.map: " + message);
  };
  require(floor_sigma_m > 0 && floor_sigma_rad > 0,
          "floor_sigma_m and floor_sigma_rad must be > 0");
  require(gravity_sigma_deg > 0, "gravity_sigma_deg must be > 0");
  require(odometry_sigma_m_per_sqrt_m >= 0 && odometry_sigma_deg_per_sqrt_m >= 0,
          "odometry_sigma_m_per_sqrt_m and odometry_sigma_deg_per_sqrt_m must be >= 0");
  require(odometry_floor_sigma_m > 0 && odometry_floor_sigma_deg > 0,
          "odometry_floor_sigma_m and odometry_floor_sigma_deg must be > 0");
  require(huber_scale > 0, "huber_scale must be > 0");
  require(outlier_chi2 > 0, "outlier_chi2 must be > 0 (22.46: chi^2 6 DOF 99.9 %)");
  require(solve_every >= 0, "solve_every must be >= 0 (0: solve only at the end)");
  require(incremental_iterations >= 1 && max_iterations >= 1, "iteration counts must be >= 1");
  require(max_pending_images >= 1, "max_pending_images must be >= 1");
  require(origin_p_m.allFinite() && origin_rpy_deg.allFinite(), "origin pose must be finite");
}

Eigen::Isometry3d TagMapParams::T_W_origin() const {
  const Eigen::Vector3d rpy = origin_rpy_deg * M_PI / 180.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = origin_p_m;
  return T;
}

std::ostream& operator<<(std::ostream& os, const TagMapSolveSummary& s) {
  return os << "TagMapSolve{converged " << s.converged << ", iterations " << s.iterations
            << ", rounds " << s.rounds << ", cost " << s.initial_cost << " -> " << s.final_cost
            << ", rejected " << s.rejected_observations << ", covariance " << s.covariance_ok
            << ", " << s.solve_time_s << " s}";
}

TagMap::TagMap(const TagMapParams& params) : params_(params) {
  params_.Validate();
  ceres::Problem::Options options;
  options.enable_fast_removal = true;  // outlier rejection removes residual blocks
  problem_ = std::make_unique<ceres::Problem>(options);
}

TagMap::~TagMap() = default;

void TagMap::AddImage(double t_s, const std::vector<TagMapObservation>& observations,
                      const TagMapOnboardEstimate& onboard) {
  const std::optional<Eigen::Vector3d>& down_C = onboard.down_C;
  if (down_C && !(down_C->allFinite() && down_C->norm() > 0.0)) {
    throw std::invalid_argument(
        "TagMap: down_C (gravity in the camera frame) must be finite and non-zero; pass "
        "std::nullopt when the vehicle's attitude is unknown");
  }
  if (onboard.T_OC && !onboard.T_OC->matrix().allFinite()) {
    throw std::invalid_argument(
        "TagMap: T_OC (the camera in the odometry frame) must be finite; pass std::nullopt "
        "when the vehicle has no odometry");
  }
  for (const TagMapObservation& o : observations) {
    const std::string what = "TagMap: observation of " + o.family + " id " + std::to_string(o.id);
    if (!(o.tag_size_m > 0.0)) throw std::invalid_argument(what + ": tag size must be > 0");
    if (!o.T_CT.matrix().allFinite() || !o.covariance.allFinite()) {
      throw std::invalid_argument(what + ": pose and covariance must be finite");
    }
    if ((o.covariance - o.covariance.transpose()).norm() > 1e-9 * o.covariance.norm() ||
        o.covariance.ldlt().vectorD().minCoeff() <= 0.0) {
      throw std::invalid_argument(what + ": covariance must be symmetric positive definite");
    }
  }
  if (onboard.T_OC) {
    if (last_p_OC_) path_m_ += (onboard.T_OC->translation() - *last_p_OC_).norm();
    last_p_OC_ = onboard.T_OC->translation();
  }
  if (observations.empty()) return;
  Image image{next_sequence_++, t_s, observations, std::nullopt, onboard.T_OC, path_m_};
  if (down_C) image.down_C = down_C->normalized();
  if (TryInsert(image)) {
    InsertPending();
    if (params_.solve_every > 0 && ++images_since_solve_ >= params_.solve_every) {
      TagMapSolveSummary summary;
      Solve(params_.incremental_iterations, &summary);
      images_since_solve_ = 0;
    }
  } else {
    pending_.push_back(std::move(image));
    if (pending_.size() > params_.max_pending_images) pending_.pop_front();
  }
}

std::optional<Eigen::Isometry3d> TagMap::InitialCameraPose(const Image& image) const {
  // From the most certain observation of a tag already in the map (or the origin tag, which
  // founds the map).
  std::optional<Eigen::Isometry3d> T_WC;
  double best_trace = std::numeric_limits<double>::infinity();
  for (const TagMapObservation& o : image.observations) {
    const auto it = tags_.find({o.family, o.id});
    std::optional<Eigen::Isometry3d> T_WT;
    if (it != tags_.end()) {
      T_WT = ToIsometry(it->second.pose);
    } else if (o.id == params_.origin_id) {
      T_WT = params_.T_W_origin();
    }
    const double trace = o.covariance.topLeftCorner<3, 3>().trace();
    if (T_WT && trace < best_trace) {
      best_trace = trace;
      T_WC = *T_WT * o.T_CT.inverse();
    }
  }
  if (T_WC || !image.T_OC) return T_WC;
  // Else chained through the odometry from a neighbour in the graph.
  for (const int neighbour : {image.sequence - 1, image.sequence + 1}) {
    const auto it = camera_of_sequence_.find(neighbour);
    if (it == camera_of_sequence_.end() || !it->second.T_OC) continue;
    return ToIsometry(it->second.pose) * it->second.T_OC->inverse() * *image.T_OC;
  }
  return std::nullopt;
}

bool TagMap::TryInsert(const Image& image) {
  const std::optional<Eigen::Isometry3d> T_WC = InitialCameraPose(image);
  if (!T_WC) return false;
  cameras_.push_back(ToBlock(*T_WC));
  double* camera = cameras_.back().data();
  problem_->AddParameterBlock(camera, 7, new SeManifold());
  const Camera& node =
      camera_of_sequence_.emplace(image.sequence, Camera{camera, image.T_OC, image.path_m})
          .first->second;
  if (image.down_C) {
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<GravityResidual, 3, 7>(
            new GravityResidual(*image.down_C, params_.gravity_sigma_deg * M_PI / 180.0)),
        nullptr, camera);
  }
  if (const auto before = camera_of_sequence_.find(image.sequence - 1);
      before != camera_of_sequence_.end()) {
    AddOdometryEdge(before->second, node);
  }
  if (const auto after = camera_of_sequence_.find(image.sequence + 1);
      after != camera_of_sequence_.end()) {
    AddOdometryEdge(node, after->second);
  }
  const Matrix6d floor = DiagonalCovariance(params_.floor_sigma_m, params_.floor_sigma_rad);
  for (const TagMapObservation& o : image.observations) {
    const Key key{o.family, o.id};
    auto it = tags_.find(key);
    if (it == tags_.end()) {
      const Eigen::Isometry3d T_WT =
          o.id == params_.origin_id ? params_.T_W_origin() : *T_WC * o.T_CT;
      TagState state{ToBlock(T_WT), T_WT, o.family, o.tag_size_m};
      it = tags_.emplace(key, state).first;
      problem_->AddParameterBlock(it->second.pose.data(), 7, new SeManifold());
      if (o.id == params_.origin_id) problem_->SetParameterBlockConstant(it->second.pose.data());
    }
    ceres::ResidualBlockId block = problem_->AddResidualBlock(
        RelativePoseResidual::Create(o.T_CT, o.covariance + floor),
        new ceres::HuberLoss(params_.huber_scale), camera, it->second.pose.data());
    edges_.push_back({block, key});
  }
  return true;
}

void TagMap::AddOdometryEdge(const Camera& earlier, const Camera& later) {
  if (!earlier.T_OC || !later.T_OC) return;
  const double path_m = later.path_m - earlier.path_m;
  const double sigma_m = std::sqrt(std::pow(params_.odometry_floor_sigma_m, 2) +
                                   std::pow(params_.odometry_sigma_m_per_sqrt_m, 2) * path_m);
  const double sigma_deg = std::sqrt(std::pow(params_.odometry_floor_sigma_deg, 2) +
                                     std::pow(params_.odometry_sigma_deg_per_sqrt_m, 2) * path_m);
  problem_->AddResidualBlock(
      RelativePoseResidual::Create(earlier.T_OC->inverse() * *later.T_OC,
                                   DiagonalCovariance(sigma_m, sigma_deg * M_PI / 180.0)),
      nullptr, earlier.pose, later.pose);
  ++odometry_edges_;
}

void TagMap::InsertPending() {
  // Newest first: images waiting before the origin tag came into view chain backwards through
  // their odometry in one pass.
  bool progress = true;
  while (progress) {
    progress = false;
    for (std::size_t i = pending_.size(); i-- > 0;) {
      if (TryInsert(pending_[i])) {
        pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(i));
        progress = true;
      }
    }
  }
}

void TagMap::Solve(int max_iterations, TagMapSolveSummary* summary) {
  if (edges_.empty()) return;
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(options, problem_.get(), &ceres_summary);
  if (summary->rounds == 0) summary->initial_cost = ceres_summary.initial_cost;
  summary->final_cost = ceres_summary.final_cost;
  summary->iterations += static_cast<int>(ceres_summary.iterations.size());
  summary->converged = ceres_summary.termination_type == ceres::CONVERGENCE;
  ++summary->rounds;
}

int TagMap::RejectOutliers() {
  int rejected = 0;
  std::map<Key, int> inliers;
  for (const Edge& edge : edges_) ++inliers[edge.tag];
  for (auto it = edges_.begin(); it != edges_.end();) {
    double squared = 0.0;
    std::array<double, 6> residual;
    problem_->EvaluateResidualBlock(it->block, false, &squared, residual.data(), nullptr);
    const double whitened_sq =
        std::inner_product(residual.begin(), residual.end(), residual.begin(), 0.0);
    // A tag's last observation stays: nothing else could tell it is wrong.
    if (whitened_sq > params_.outlier_chi2 && inliers[it->tag] > 1) {
      problem_->RemoveResidualBlock(it->block);
      --inliers[it->tag];
      ++tags_.at(it->tag).rejected;
      ++rejected;
      it = edges_.erase(it);
    } else {
      ++it;
    }
  }
  return rejected;
}

bool TagMap::ComputeCovariances() {
  ceres::Covariance::Options options;
  options.num_threads = 1;
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (auto& [key, tag] : tags_) {
    if (!problem_->IsParameterBlockConstant(tag.pose.data())) {
      blocks.emplace_back(tag.pose.data(), tag.pose.data());
    }
  }
  if (blocks.empty()) return true;
  if (!covariance.Compute(blocks, problem_.get())) return false;
  for (auto& [key, tag] : tags_) {
    tag.has_covariance = false;
    if (problem_->IsParameterBlockConstant(tag.pose.data())) continue;
    // Tangent space of the product manifold: [rotation (left, in W); translation].
    Matrix6d tangent;
    covariance.GetCovarianceBlockInTangentSpace(tag.pose.data(), tag.pose.data(), tangent.data());
    tangent.transposeInPlace();  // Ceres writes row-major
    Eigen::PermutationMatrix<6> swap;
    swap.indices() << 3, 4, 5, 0, 1, 2;
    tag.covariance = swap * tangent * swap.transpose();
    tag.has_covariance = true;
  }
  return true;
}

TagMapSolveSummary TagMap::Optimize() {
  const auto start = std::chrono::steady_clock::now();
  TagMapSolveSummary summary;
  InsertPending();
  for (int round = 0; round < 5 && !edges_.empty(); ++round) {
    Solve(params_.max_iterations, &summary);
    const int rejected = RejectOutliers();
    summary.rejected_observations += rejected;
    if (rejected == 0) break;
  }
  summary.covariance_ok = ComputeCovariances();
  summary.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

std::vector<MappedTag> TagMap::Tags() const {
  std::map<Key, int> inliers;
  for (const Edge& edge : edges_) ++inliers[edge.tag];
  std::vector<MappedTag> tags;
  for (const auto& [key, tag] : tags_) {
    MappedTag mapped;
    mapped.family = key.first;
    mapped.id = key.second;
    mapped.size_m = tag.size_m;
    mapped.T_WT = ToIsometry(tag.pose);
    mapped.T_WT_initial = tag.T_WT_initial;
    mapped.covariance = tag.covariance;
    mapped.has_covariance = tag.has_covariance;
    const auto it = inliers.find(key);
    mapped.observations = it == inliers.end() ? 0 : it->second;
    mapped.rejected = tag.rejected;
    tags.push_back(mapped);
  }
  return tags;
}

}  // namespace aperture::perception
