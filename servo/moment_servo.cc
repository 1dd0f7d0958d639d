#include "servo/moment_servo.h"

#include <visp3/core/vpMomentAlpha.h>
#include <visp3/core/vpMomentAreaNormalized.h>
#include <visp3/core/vpMomentCentered.h>
#include <visp3/core/vpMomentDatabase.h>
#include <visp3/core/vpMomentGravityCenter.h>
#include <visp3/core/vpMomentGravityCenterNormalized.h>
#include <visp3/core/vpMomentObject.h>
#include <visp3/visual_features/vpFeatureMomentAlpha.h>
#include <visp3/visual_features/vpFeatureMomentAreaNormalized.h>
#include <visp3/visual_features/vpFeatureMomentGravityCenterNormalized.h>
#include <visp3/vs/vpServo.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "servo/internal/visp_conversions.h"
#include "servo/polygon_moments.h"

namespace aperture::servo {
namespace {

// Highest moment order used: alpha's reference needs the third-order centred moments (mu30 ..
// mu03), and so does its interaction matrix (vpFeatureMomentAlpha).
constexpr unsigned int kMomentOrder = 3;
// A forward camera's optical axis is ~90 deg off z_B, a downward one ~0 (or 180) deg: 60 deg
// separates them with margin for a tilted mount.
const double kMaxOrientationAxisAngleRad = M_PI / 3.0;

void RequirePolygon(const std::vector<Eigen::Vector2d>& polygon_n, const char* what) {
  if (polygon_n.size() < 3) {
    throw std::invalid_argument(std::string("MomentServo::") + what + ": the polygon has " +
                                std::to_string(polygon_n.size()) +
                                " vertices; pass at least 3 in normalized image coordinates");
  }
  for (const Eigen::Vector2d& p : polygon_n) {
    if (!p.allFinite()) {
      throw std::invalid_argument(std::string("MomentServo::") + what +
                                  ": a polygon vertex is not finite");
    }
  }
}

// Twice the signed area by the shoelace formula, in the image's (x right, y down) axes.
double TwiceSignedArea(const std::vector<Eigen::Vector2d>& polygon_n) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon_n.size(); ++i) {
    const Eigen::Vector2d& a = polygon_n[i];
    const Eigen::Vector2d& b = polygon_n[(i + 1) % polygon_n.size()];
    sum += a.x() * b.y() - b.x() * a.y();
  }
  return sum;
}

// vpMomentObject whose basic moments are set from outside (ViSP 3.5 keeps set() protected).
struct ClosedFormMomentObject : vpMomentObject {
  explicit ClosedFormMomentObject(unsigned int max_order) : vpMomentObject(max_order) {}
  using vpMomentObject::set;
};

// The moment primitives of one view, in a database (vpMoment* find each other by name).
struct MomentSet {
  ClosedFormMomentObject object{kMomentOrder};
  vpMomentDatabase database;
  vpMomentGravityCenter gravity;
  vpMomentCentered centered;
  vpMomentAreaNormalized area_normalized{1.0, 1.0};  // a*, Z* set in Compute
  vpMomentGravityCenterNormalized gravity_normalized;
  vpMomentAlpha alpha;

  // alpha_reference: empty for the desired view (ViSP's reference mode, alpha in [-pi/2, pi/2]);
  // the desired view's [mu30, mu21, mu12, mu03] and alpha otherwise ([-pi, pi]).
  explicit MomentSet(const std::vector<double>& mu3_reference = {}, double alpha_reference = 0.0)
      : alpha(mu3_reference.empty() ? vpMomentAlpha()
                                    : vpMomentAlpha(mu3_reference, alpha_reference)) {
    object.setType(vpMomentObject::DENSE_POLYGON);
    gravity.linkTo(database);
    centered.linkTo(database);
    area_normalized.linkTo(database);
    gravity_normalized.linkTo(database);
    alpha.linkTo(database);
  }

  // ViSP computes each moment from those it depends on: gravity centre, centred moments, then
  // the normalized area (uses a*, Z*), the normalized centre (uses a_n) and alpha.
  void Compute(const std::vector<Eigen::Vector2d>& polygon_n, double desired_area_n2,
               double desired_depth_m) {
    // Closed-form moments (servo/polygon_moments.h) instead of object.fromVector: the same
    // values (checked in tests/servo/polygon_moments_test.cc) at a fraction of the cost.
    const Eigen::Matrix4d m = PolygonMoments(polygon_n);
    for (unsigned int p = 0; p <= kMomentOrder; ++p) {
      for (unsigned int q = 0; p + q <= kMomentOrder; ++q) object.set(p, q, m(p, q));
    }
    database.updateAll(object);
    gravity.compute();
    centered.compute();
    area_normalized.setDesiredArea(desired_area_n2);
    area_normalized.setDesiredDepth(desired_depth_m);
    area_normalized.compute();
    gravity_normalized.compute();
    alpha.compute();
  }

  double area() const { return object.get(0, 0); }
  // (mu20 - mu02)^2 + 4 mu11^2 over (mu20 + mu02)^2: 0 for isotropic second moments, 1 for a
  // segment.
  double OrientationAnisotropy() const {
    const double mu20 = centered.get(2, 0), mu02 = centered.get(0, 2), mu11 = centered.get(1, 1);
    const double trace = mu20 + mu02;
    if (trace <= 0.0) return 0.0;
    return ((mu20 - mu02) * (mu20 - mu02) + 4.0 * mu11 * mu11) / (trace * trace);
  }
  std::vector<double> ThirdOrderCentred() const {
    return {centered.get(3, 0), centered.get(2, 1), centered.get(1, 2), centered.get(0, 3)};
  }
};

// The features of one view on the plane 1/Z = C (A = B = 0).
struct FeatureSet {
  vpFeatureMomentGravityCenterNormalized gravity_normalized;
  vpFeatureMomentAreaNormalized area_normalized;
  vpFeatureMomentAlpha alpha;

  FeatureSet(MomentSet* moments, double C)
      : gravity_normalized(moments->database, 0.0, 0.0, C),
        area_normalized(moments->database, 0.0, 0.0, C),
        alpha(moments->database, 0.0, 0.0, C) {}

  // vpFeatureMoment::update reads the moment values and computes the interaction matrix.
  void Update(double C, bool with_alpha) {
    gravity_normalized.update(0.0, 0.0, C);
    area_normalized.update(0.0, 0.0, C);
    if (with_alpha) alpha.update(0.0, 0.0, C);
  }
};

}  // namespace

struct MomentServo::Impl {
  double desired_area_n2 = 0.0;
  double desired_depth_m = 0.0;
  // Desired view (reference alpha) and current view (alpha relative to it); rebuilt by
  // SetDesired because vpMomentAlpha takes its reference at construction.
  std::unique_ptr<MomentSet> desired_moments;
  std::unique_ptr<FeatureSet> desired_features;
  std::unique_ptr<MomentSet> moments;
  std::unique_ptr<FeatureSet> features;
  std::unique_ptr<vpServo> task;
};

void MomentServoParams::Validate() const {
  gain.Validate();
  if (!std::isfinite(min_area_n2) || min_area_n2 <= 0.0) {
    throw std::invalid_argument("MomentServoParams.min_area_n2 = " + std::to_string(min_area_n2) +
                                " must be finite and > 0 (normalized image units^2)");
  }
  if (!std::isfinite(min_orientation_anisotropy) || min_orientation_anisotropy <= 0.0 ||
      min_orientation_anisotropy >= 1.0) {
    throw std::invalid_argument("MomentServoParams.min_orientation_anisotropy = " +
                                std::to_string(min_orientation_anisotropy) + " must lie in (0, 1)");
  }
}

MomentServo::MomentServo(const MomentServoParams& params, const Eigen::Isometry3d& T_BC)
    : params_(params), T_BC_(T_BC), impl_(std::make_unique<Impl>()) {
  params_.Validate();
  RequireRigidMount(T_BC, "MomentServo");
  const Eigen::Matrix3d R_BC = T_BC.linear();
  if (params_.yaw == YawMode::kOrientation) {
    const double cos_axis = std::abs(R_BC.col(2).z());  // optical axis z_C against z_B
    if (cos_axis < std::cos(kMaxOrientationAxisAngleRad)) {
      throw std::invalid_argument(
          "MomentServo: yaw = orientation needs a camera looking along z_B (downward or upward, "
          "within 60 deg), but the optical axis is " +
          std::to_string(std::acos(cos_axis) * 180.0 / M_PI) +
          " deg off it: the image orientation alpha would observe roll, not yaw; use yaw = hold");
    }
  }
}

MomentServo::~MomentServo() = default;

bool MomentServo::has_desired() const { return impl_->task != nullptr; }

void MomentServo::SetDesired(const std::vector<Eigen::Vector2d>& polygon_n, double depth_m) {
  RequirePolygon(polygon_n, "SetDesired");
  if (!std::isfinite(depth_m) || depth_m <= 0.0) {
    throw std::invalid_argument("MomentServo::SetDesired: depth_m = " + std::to_string(depth_m) +
                                " must be finite and > 0 (distance of the target plane in front "
                                "of the camera at the goal) [m]");
  }
  const double area = 0.5 * std::abs(TwiceSignedArea(polygon_n));
  if (area < params_.min_area_n2) {
    throw std::invalid_argument("MomentServo::SetDesired: the desired polygon's area " +
                                std::to_string(area) +
                                " is below min_area_n2 = " + std::to_string(params_.min_area_n2));
  }
  const bool with_alpha = params_.yaw == YawMode::kOrientation;
  auto impl = std::make_unique<Impl>();
  impl->desired_area_n2 = area;
  impl->desired_depth_m = depth_m;
  const double C = 1.0 / depth_m;
  impl->desired_moments = std::make_unique<MomentSet>();
  impl->desired_moments->Compute(polygon_n, area, depth_m);
  if (with_alpha &&
      impl->desired_moments->OrientationAnisotropy() < params_.min_orientation_anisotropy) {
    throw std::invalid_argument(
        "MomentServo::SetDesired: the desired polygon's second moments are isotropic (a square "
        "or regular polygon), so its orientation alpha is undefined; use yaw = hold, or the "
        "point servo on its corners");
  }
  impl->desired_features = std::make_unique<FeatureSet>(impl->desired_moments.get(), C);
  impl->desired_features->Update(C, with_alpha);
  impl->moments = std::make_unique<MomentSet>(impl->desired_moments->ThirdOrderCentred(),
                                              impl->desired_moments->alpha.get());
  impl->features = std::make_unique<FeatureSet>(impl->moments.get(), C);
  impl->task = std::make_unique<vpServo>();
  internal::ConfigureDroneTask(params_.gain, T_BC_, with_alpha, impl->task.get());
  impl->task->addFeature(impl->features->gravity_normalized,
                         impl->desired_features->gravity_normalized);
  impl->task->addFeature(impl->features->area_normalized, impl->desired_features->area_normalized);
  if (with_alpha) impl->task->addFeature(impl->features->alpha, impl->desired_features->alpha);
  impl_ = std::move(impl);
}

ServoStepResult MomentServo::Step(const std::vector<Eigen::Vector2d>& polygon_n) {
  if (!has_desired()) {
    throw std::invalid_argument("MomentServo::Step: no desired view; call SetDesired first");
  }
  RequirePolygon(polygon_n, "Step");
  const bool with_alpha = params_.yaw == YawMode::kOrientation;
  ServoStepResult result;
  result.error = Eigen::VectorXd::Zero(with_alpha ? 4 : 3);
  if (0.5 * std::abs(TwiceSignedArea(polygon_n)) < params_.min_area_n2) {
    result.status = ServoStatus::kDegenerateFeatures;
    return result;
  }
  impl_->moments->Compute(polygon_n, impl_->desired_area_n2, impl_->desired_depth_m);
  if (with_alpha && impl_->moments->OrientationAnisotropy() < params_.min_orientation_anisotropy) {
    result.status = ServoStatus::kDegenerateFeatures;
    return result;
  }
  impl_->features->Update(1.0 / impl_->desired_depth_m, with_alpha);
  const vpColVector u = impl_->task->computeControlLaw();
  internal::FillReference(u, T_BC_, &result.reference, &result.twist_C);
  result.error = internal::ToEigen(impl_->task->getError());
  result.error_norm = result.error.norm();
  return result;
}

}  // namespace aperture::servo
