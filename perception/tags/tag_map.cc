#include "perception/tags/tag_map.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
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

// The edge of one observation (see the header); parameters: T_WC and T_WT blocks.
struct ObservationResidual {
  ObservationResidual(const Eigen::Isometry3d& T_CT, const Matrix6d& sqrt_information)
      : q_CT_measured(T_CT.rotation()),
        p_CT_measured(T_CT.translation()),
        sqrt_information(sqrt_information) {}

  template <typename S>
  bool operator()(const S* camera, const S* tag, S* residual) const {
    using Quaternion = Eigen::Quaternion<S>;
    using Vector3 = Eigen::Matrix<S, 3, 1>;
    const Eigen::Map<const Quaternion> q_WC(camera);
    const Eigen::Map<const Vector3> p_WC(camera + 4);
    const Eigen::Map<const Quaternion> q_WT(tag);
    const Eigen::Map<const Vector3> p_WT(tag + 4);
    const Quaternion q_CW = q_WC.conjugate();
    const Vector3 p_CT = q_CW * (p_WT - p_WC);
    Quaternion q_error = (q_CW * q_WT) * q_CT_measured.conjugate().template cast<S>();
    if (q_error.w() < S(0)) q_error.coeffs() = -q_error.coeffs();
    Eigen::Matrix<S, 6, 1> error;
    error.template head<3>() = p_CT - p_CT_measured.template cast<S>();
    error.template tail<3>() = S(2) * q_error.vec();  // Log for small errors
    Eigen::Map<Eigen::Matrix<S, 6, 1>> whitened(residual);
    whitened = sqrt_information.template cast<S>() * error;
    return true;
  }

  Eigen::Quaterniond q_CT_measured;
  Eigen::Vector3d p_CT_measured;
  Matrix6d sqrt_information;
};

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
                      const std::optional<Eigen::Vector3d>& down_C) {
  if (down_C && !(down_C->allFinite() && down_C->norm() > 0.0)) {
    throw std::invalid_argument(
        "TagMap: down_C (gravity in the camera frame) must be finite and non-zero; pass "
        "std::nullopt when the vehicle's attitude is unknown");
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
  if (observations.empty()) return;
  Image image{t_s, observations, std::nullopt};
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

bool TagMap::TryInsert(const Image& image) {
  // The camera pose from the most certain observation of a tag already in the map (or the
  // origin tag, which founds the map).
  const TagMapObservation* anchor = nullptr;
  Eigen::Isometry3d T_WT_anchor;
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
      anchor = &o;
      T_WT_anchor = *T_WT;
    }
  }
  if (!anchor) return false;
  const Eigen::Isometry3d T_WC = T_WT_anchor * anchor->T_CT.inverse();
  cameras_.push_back(ToBlock(T_WC));
  double* camera = cameras_.back().data();
  problem_->AddParameterBlock(camera, 7, new SeManifold());
  if (image.down_C) {
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<GravityResidual, 3, 7>(
            new GravityResidual(*image.down_C, params_.gravity_sigma_deg * M_PI / 180.0)),
        nullptr, camera);
  }
  const Matrix6d floor =
      (Eigen::Matrix<double, 6, 1>() << Eigen::Vector3d::Constant(params_.floor_sigma_m),
       Eigen::Vector3d::Constant(params_.floor_sigma_rad))
          .finished()
          .cwiseAbs2()
          .asDiagonal();
  for (const TagMapObservation& o : image.observations) {
    const Key key{o.family, o.id};
    auto it = tags_.find(key);
    if (it == tags_.end()) {
      const Eigen::Isometry3d T_WT =
          o.id == params_.origin_id ? params_.T_W_origin() : T_WC * o.T_CT;
      TagState state{ToBlock(T_WT), T_WT, o.family, o.tag_size_m};
      it = tags_.emplace(key, state).first;
      problem_->AddParameterBlock(it->second.pose.data(), 7, new SeManifold());
      if (o.id == params_.origin_id) problem_->SetParameterBlockConstant(it->second.pose.data());
    }
    // L with L^T L = Sigma^-1: the inverse of the Cholesky factor of Sigma (Sigma = U^T U).
    const Matrix6d sigma = o.covariance + floor;
    const Eigen::LLT<Matrix6d> llt(sigma);
    const Matrix6d sqrt_information =
        llt.matrixL().solve(Matrix6d::Identity());  // L_sigma^-1: (L^-1)^T L^-1 = Sigma^-1
    auto* cost = new ceres::AutoDiffCostFunction<ObservationResidual, 6, 7, 7>(
        new ObservationResidual(o.T_CT, sqrt_information));
    ceres::ResidualBlockId block = problem_->AddResidualBlock(
        cost, new ceres::HuberLoss(params_.huber_scale), camera, it->second.pose.data());
    edges_.push_back({block, key});
  }
  return true;
}

void TagMap::InsertPending() {
  bool progress = true;
  while (progress) {
    progress = false;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (TryInsert(*it)) {
        it = pending_.erase(it);
        progress = true;
      } else {
        ++it;
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
