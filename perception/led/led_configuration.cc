#include "perception/led/led_configuration.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "config/param_reader.h"
#include "config/regular_file.h"

namespace aperture::perception {
namespace {

[[noreturn]] void Reject(const std::string& source, const std::string& reason) {
  throw std::invalid_argument("LED configuration " + source + ": " + reason);
}

// Largest residual after the best proper rigid alignment (Kabsch) of `from` onto `to`.
double RigidAlignmentResidual(const std::vector<Eigen::Vector3d>& from,
                              const std::vector<Eigen::Vector3d>& to) {
  const std::size_t n = from.size();
  Eigen::Vector3d mean_from = Eigen::Vector3d::Zero(), mean_to = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_from += from[i] / n;
    mean_to += to[i] / n;
  }
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) H += (from[i] - mean_from) * (to[i] - mean_to).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d R = svd.matrixV() * D * svd.matrixU().transpose();
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    worst = std::max(worst, (R * (from[i] - mean_from) + mean_to - to[i]).norm());
  }
  return worst;
}

std::string FormatPoint(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  return out.str();
}

}  // namespace

LedConfiguration::LedConfiguration(std::vector<Eigen::Vector3d> p_T, std::string source)
    : p_T_(std::move(p_T)), source_(std::move(source)) {
  const int n = size();
  if (n < kMinLeds || n > kMaxLeds) {
    Reject(source_, "has " + std::to_string(n) + " LEDs; give between " + std::to_string(kMinLeds) +
                        " and " + std::to_string(kMaxLeds));
  }
  for (int i = 0; i < n; ++i) {
    if (!p_T_[i].allFinite()) Reject(source_, "LED " + std::to_string(i) + " is not finite");
    for (int j = i + 1; j < n; ++j) {
      if ((p_T_[i] - p_T_[j]).norm() < kMinLedSpacing_m) {
        Reject(source_, "LEDs " + std::to_string(i) + " " + FormatPoint(p_T_[i]) + " and " +
                            std::to_string(j) + " " + FormatPoint(p_T_[j]) +
                            " are closer than 1 cm; their blobs would merge");
      }
    }
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : p_T_) mean += p / n;
  Eigen::MatrixXd centred(3, n);
  for (int i = 0; i < n; ++i) centred.col(i) = p_T_[i] - mean;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeFullU);
  const Eigen::Vector3d normal = svd.matrixU().col(2);
  const double off_plane = (normal.transpose() * centred).cwiseAbs().maxCoeff();
  if (off_plane < kCoplanarTolerance_m) {
    Reject(source_, "the LEDs are coplanar (largest distance to their plane " +
                        std::to_string(off_plane * 1e3) +
                        " mm); move at least one LED 3 mm or more out of the plane");
  }
  std::vector<int> permutation(n);
  std::iota(permutation.begin(), permutation.end(), 0);
  std::vector<Eigen::Vector3d> permuted(n);
  while (std::next_permutation(permutation.begin(), permutation.end())) {
    for (int i = 0; i < n; ++i) permuted[i] = p_T_[permutation[i]];
    const double residual = RigidAlignmentResidual(p_T_, permuted);
    if (residual < kSymmetryTolerance_m) {
      std::string mapping;
      for (int i = 0; i < n; ++i) {
        mapping += (i ? ", " : "") + std::to_string(i) + "->" + std::to_string(permutation[i]);
      }
      Reject(source_, "is symmetric: a rigid motion maps the LEDs onto each other (" + mapping +
                          ") within " + std::to_string(residual * 1e3) +
                          " mm (tolerance 15 mm), so their correspondences are ambiguous; move "
                          "one LED");
    }
  }
}

LedConfiguration LedConfiguration::Load(const std::string& path) {
  config::RequireRegularFileIfPresent(path, "LED configuration file");
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error("cannot read LED configuration file " + path);
  return Parse(stream, path);
}

LedConfiguration LedConfiguration::Parse(std::istream& yaml, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("LED configuration " + source + " is not valid YAML: " + e.what());
  }
  config::ParamReader reader(root, source);
  if (!reader.Has("leds")) Reject(source, "has no key `leds: [[x, y, z], ...]` (metres, frame T)");
  std::vector<Eigen::Vector3d> p_T;
  reader.Read("leds", &p_T);
  reader.RejectUnknownKeys();
  return LedConfiguration(std::move(p_T), source);
}

LedConfiguration LedConfiguration::Default() {
  // Irregular on purpose: four LEDs at uneven angles around the rim, one lowered inside, so no
  // relabelling comes close to a rigid motion (a near-regular pentagon would be ambiguous at
  // lambda_r = 5 px). Four lie in the arm plane outside the body, one hangs below it (z < 0),
  // where the `led` scenario's ground camera sees them all; the scenario uses this same layout.
  return LedConfiguration({{0.000, 0.105, 0.000},
                           {0.100, 0.010, 0.000},
                           {0.020, -0.090, -0.030},
                           {-0.090, -0.040, 0.000},
                           {-0.040, 0.040, -0.080}},
                          "built-in default");
}

}  // namespace aperture::perception
