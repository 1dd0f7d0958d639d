#include "perception/led/p3p_solver.h"

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opengv/absolute_pose/modules/main.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

void SolveKneip(const std::array<Eigen::Vector3d, 3>& f_C,
                const std::array<Eigen::Vector3d, 3>& p_T,
                std::vector<Eigen::Isometry3d>* solutions) {
  opengv::bearingVectors_t bearings(f_C.begin(), f_C.end());
  opengv::points_t points(p_T.begin(), p_T.end());
  opengv::transformations_t poses;
  opengv::absolute_pose::modules::p3p_kneip_main(bearings, points, poses);
  for (const auto& T_TC : poses) {  // OpenGV returns [R_TC | p_TC]
    if (!T_TC.allFinite()) continue;
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    T_CT.linear() = T_TC.leftCols<3>().transpose();
    T_CT.translation() = -T_CT.linear() * T_TC.col(3);
    solutions->push_back(T_CT);
  }
}

void SolveAp3p(const std::array<Eigen::Vector3d, 3>& f_C,
               const std::array<Eigen::Vector3d, 3>& p_T,
               std::vector<Eigen::Isometry3d>* solutions) {
  cv::Matx<double, 3, 3> object;
  cv::Matx<double, 3, 2> image;
  for (int i = 0; i < 3; ++i) {
    if (f_C[i].z() <= 1e-9) return;  // AP3P works on normalized image points only
    for (int k = 0; k < 3; ++k) object(i, k) = p_T[i][k];
    image(i, 0) = f_C[i].x() / f_C[i].z();
    image(i, 1) = f_C[i].y() / f_C[i].z();
  }
  std::vector<cv::Mat> rvecs, tvecs;
  const cv::Matx33d K = cv::Matx33d::eye();
  cv::solveP3P(cv::Mat(object).reshape(3, 3), cv::Mat(image).reshape(2, 3), K, cv::noArray(),
               rvecs, tvecs, cv::SOLVEPNP_AP3P);
  for (std::size_t s = 0; s < rvecs.size(); ++s) {
    cv::Matx33d R;
    cv::Rodrigues(rvecs[s], R);
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T_CT.linear()(r, c) = R(r, c);
      T_CT.translation()[r] = tvecs[s].at<double>(r);
    }
    if (T_CT.matrix().allFinite()) solutions->push_back(T_CT);
  }
}

}  // namespace

P3pMethod ParseP3pMethod(const std::string& name) {
  if (name == "kneip") return P3pMethod::kKneip;
  if (name == "ap3p") return P3pMethod::kAp3p;
  throw std::invalid_argument("unknown P3P method '" + name + "'; use kneip or ap3p");
}

std::string P3pMethodName(P3pMethod method) {
  return method == P3pMethod::kKneip ? "kneip" : "ap3p";
}

void SolveP3p(P3pMethod method, const std::array<Eigen::Vector3d, 3>& f_C,
              const std::array<Eigen::Vector3d, 3>& p_T,
              std::vector<Eigen::Isometry3d>* solutions) {
  solutions->clear();
  if (method == P3pMethod::kKneip) {
    SolveKneip(f_C, p_T, solutions);
  } else {
    SolveAp3p(f_C, p_T, solutions);
  }
  // Both solvers turn near-real complex roots of their quartic into poses that do not reproduce
  // the bearings; drop them (and points behind the camera centre) so that callers only vote
  // with true solutions. 1e-4 rad is far above the round-off of a genuine solution.
  constexpr double kMaxBearingError_rad = 1e-4;
  solutions->erase(
      std::remove_if(solutions->begin(), solutions->end(),
                     [&](const Eigen::Isometry3d& T_CT) {
                       for (int i = 0; i < 3; ++i) {
                         const Eigen::Vector3d p_C = T_CT * p_T[i];
                         if (p_C.cross(f_C[i]).norm() > kMaxBearingError_rad * p_C.norm() ||
                             p_C.dot(f_C[i]) <= 0.0) {
                           return true;
                         }
                       }
                       return false;
                     }),
      solutions->end());
}

}  // namespace aperture::perception
