#include "perception/gap/gap_detector.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "control/require.h"
#include "control/so3.h"
#include "perception/gap/canny_edge_detector.h"

namespace aperture::perception {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using control::Skew;

// Rotation R_VC of a virtual pinhole camera V looking along axis_C (unit), x_V close to x_C.
// Gnomonic coordinates in V map straight 3D lines to straight lines whatever the lens.
Mat3 VirtualCameraRotation(const Vec3& axis_C) {
  const Vec3 z = axis_C.normalized();
  Vec3 x = Vec3::UnitX() - z.x() * z;
  if (x.norm() < 1e-6) x = Vec3::UnitY() - z.y() * z;
  x.normalize();
  Mat3 R_CV;
  R_CV.col(0) = x;
  R_CV.col(1) = z.cross(x);
  R_CV.col(2) = z;
  return R_CV.transpose();
}

// Gnomonic coordinates (x/z, y/z) of bearing b_V; false when not in front of V.
bool Gnomonic(const Vec3& b_V, Vec2* uv) {
  if (b_V.z() < 0.05) return false;
  *uv = b_V.head<2>() / b_V.z();
  return true;
}

double SignedArea(const std::array<Vec2, 4>& q) {
  double a = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Vec2& p = q[k];
    const Vec2& n = q[(k + 1) % 4];
    a += p.x() * n.y() - n.x() * p.y();
  }
  return 0.5 * a;
}

// Bilinear sample of a CV_8UC1 image; caller keeps (x, y) inside [0, w-1) x [0, h-1).
double Sample(const cv::Mat& gray, double x, double y) {
  const int x0 = static_cast<int>(x);
  const int y0 = static_cast<int>(y);
  const double ax = x - x0;
  const double ay = y - y0;
  const uint8_t* r0 = gray.ptr<uint8_t>(y0) + x0;
  const uint8_t* r1 = gray.ptr<uint8_t>(y0 + 1) + x0;
  return (1.0 - ay) * ((1.0 - ax) * r0[0] + ax * r0[1]) + ay * ((1.0 - ax) * r1[0] + ax * r1[1]);
}

bool Inside(const cv::Mat& gray, const Vec2& p, double border) {
  return p.x() >= border && p.y() >= border && p.x() < gray.cols - 1 - border &&
         p.y() < gray.rows - 1 - border;
}

// A convex quadrangle from one contour: corners as bearings (positive orientation as seen by
// the camera, i.e. clockwise on screen) and pixels.
struct Quad {
  std::array<Vec3, 4> bearing_C;
  std::array<Vec2, 4> px;
  double contrast = 0.0;  // mean(outside) - mean(inside) across its sides [gray levels]
};

struct Side {
  std::vector<Vec3> bearings_C;    // sub-pixel edge samples
  Vec3 normal_C = Vec3::Zero();    // great-circle (plane through C) normal of the fitted edge
};

}  // namespace

void ValidateGapDetectorParams(const GapDetectorParams& p) {
  p.ValidatePattern("GapDetectorParams");
  control::Require(p.canny_low > 0.0, "GapDetectorParams.canny_low", p.canny_low, "must be > 0");
  control::Require(p.canny_high >= p.canny_low, "GapDetectorParams.canny_high", p.canny_high,
                   "must be >= canny_low");
  control::Require(p.min_perimeter_px > 0.0, "GapDetectorParams.min_perimeter_px",
                   p.min_perimeter_px, "must be > 0");
  control::Require(p.approx_epsilon_ratio > 0.0 && p.approx_epsilon_ratio < 0.25,
                   "GapDetectorParams.approx_epsilon_ratio", p.approx_epsilon_ratio,
                   "must be in (0, 0.25)");
  control::Require(p.approx_epsilon_max_ratio >= p.approx_epsilon_ratio &&
                       p.approx_epsilon_max_ratio < 0.25,
                   "GapDetectorParams.approx_epsilon_max_ratio", p.approx_epsilon_max_ratio,
                   "must be in [approx_epsilon_ratio, 0.25)");
  control::Require(p.min_side_px > 0.0, "GapDetectorParams.min_side_px", p.min_side_px,
                   "must be > 0");
  control::Require(p.area_ratio_tolerance > 1.0, "GapDetectorParams.area_ratio_tolerance",
                   p.area_ratio_tolerance, "must be > 1");
  control::Require(p.min_contrast > 0.0, "GapDetectorParams.min_contrast", p.min_contrast,
                   "must be > 0");
  control::RequireInRange(p.edge_search_px, 2, 16, "GapDetectorParams.edge_search_px");
  control::Require(p.edge_sample_step_px > 0.0, "GapDetectorParams.edge_sample_step_px",
                   p.edge_sample_step_px, "must be > 0");
  control::Require(p.max_samples_per_side >= 4, "GapDetectorParams.max_samples_per_side",
                   p.max_samples_per_side, "must be >= 4");
  control::Require(p.corner_exclusion >= 0.0 && p.corner_exclusion < 0.45,
                   "GapDetectorParams.corner_exclusion", p.corner_exclusion,
                   "must be in [0, 0.45)");
  control::Require(p.max_corner_rms_px > 0.0, "GapDetectorParams.max_corner_rms_px",
                   p.max_corner_rms_px, "must be > 0");
  control::Require(p.pixel_sigma_px > 0.0, "GapDetectorParams.pixel_sigma_px", p.pixel_sigma_px,
                   "must be > 0");
  control::Require(p.refinement_iterations >= 0, "GapDetectorParams.refinement_iterations",
                   p.refinement_iterations, "must be >= 0");
  control::Require(p.roi_margin_ratio >= 0.0, "GapDetectorParams.roi_margin_ratio",
                   p.roi_margin_ratio, "must be >= 0");
  control::Require(p.roi_margin_px >= 0, "GapDetectorParams.roi_margin_px", p.roi_margin_px,
                   "must be >= 0");
}

Eigen::Isometry3d NearestGapLabelling(const Eigen::Isometry3d& T_CG,
                                      const Eigen::Matrix3d& R_CG_expected) {
  Eigen::Isometry3d turned = T_CG;
  turned.linear() = T_CG.linear() * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();  // Rz(pi)
  // The nearer rotation has the larger trace of R_expected^T R (trace = 1 + 2 cos(angle)).
  const double kept = (R_CG_expected.transpose() * T_CG.linear()).trace();
  const double other = (R_CG_expected.transpose() * turned.linear()).trace();
  return other > kept ? turned : T_CG;
}

std::string GapDetectionStatusName(GapDetectionStatus status) {
  switch (status) {
    case GapDetectionStatus::kDetected: return "detected";
    case GapDetectionStatus::kNoCandidate: return "no_candidate";
    case GapDetectionStatus::kReprojectionRejected: return "reprojection_rejected";
  }
  return "unknown";
}

const std::vector<std::pair<std::string, GapDetectionStatus>>& GapDetectionStatusNames() {
  static const std::vector<std::pair<std::string, GapDetectionStatus>> kNames = [] {
    std::vector<std::pair<std::string, GapDetectionStatus>> names;
    for (GapDetectionStatus status :
         {GapDetectionStatus::kDetected, GapDetectionStatus::kNoCandidate,
          GapDetectionStatus::kReprojectionRejected}) {
      names.emplace_back(GapDetectionStatusName(status), status);
    }
    return names;
  }();
  return kNames;
}

struct GapDetector::Impl {
  cv::Mat bearing_table;  // CV_32FC3, unit bearing of every pixel centre
  cv::Mat gray;
  CannyEdgeDetector canny;
  cv::Mat edges;
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Point2f> gnomonic;
  std::vector<cv::Point2f> polygon;

  Vec3 TableBearing(const cv::Point& p) const {
    const cv::Vec3f& b = bearing_table.at<cv::Vec3f>(p.y, p.x);
    return Vec3(b[0], b[1], b[2]);
  }
};

GapDetector::GapDetector(const GapDetectorParams& params, std::shared_ptr<const CameraModel> camera)
    : params_(params), camera_(std::move(camera)), impl_(std::make_unique<Impl>()) {
  ValidateGapDetectorParams(params_);
  if (!camera_) throw std::invalid_argument("GapDetector: camera model is null; pass a calibrated camera");
  impl_->bearing_table.create(camera_->height(), camera_->width(), CV_32FC3);
  for (int y = 0; y < camera_->height(); ++y) {
    for (int x = 0; x < camera_->width(); ++x) {
      const Vec3 b = camera_->Unproject(Vec2(x, y));
      impl_->bearing_table.at<cv::Vec3f>(y, x) = cv::Vec3f(b.x(), b.y(), b.z());
    }
  }
}

GapDetector::~GapDetector() = default;

std::vector<Vec3> GapDetector::ModelCorners() const {
  std::vector<Vec3> corners;
  for (const Vec2& size : {params_.outer_size_m, params_.inner_size_m}) {
    const double hx = 0.5 * size.x();
    const double hy = 0.5 * size.y();
    corners.emplace_back(-hx, -hy, 0.0);
    corners.emplace_back(hx, -hy, 0.0);
    corners.emplace_back(hx, hy, 0.0);
    corners.emplace_back(-hx, hy, 0.0);
  }
  return corners;
}

namespace {

// Everything one detection attempt needs, kept out of the header.
class Attempt {
 public:
  Attempt(const GapDetectorParams& params, const CameraModel& camera, const cv::Mat& gray,
          std::vector<Vec3> model_corners_G)
      : p_(params), camera_(camera), gray_(gray), model_G_(std::move(model_corners_G)) {}

  // Mean intensity outside minus inside along the quad's sides. Sample points follow the
  // sides as great circles (curved in a fisheye image), not the chords between the corners.
  double Contrast(const Quad& q) const {
    double outside = 0.0, inside = 0.0;
    int n = 0;
    for (int k = 0; k < 4; ++k) {
      const Vec3& b0 = q.bearing_C[k];
      const Vec3& b1 = q.bearing_C[(k + 1) % 4];
      const double offset = std::clamp(0.1 * (q.px[(k + 1) % 4] - q.px[k]).norm(), 1.5, 4.0);
      for (double t : {0.3, 0.5, 0.7}) {
        Vec2 m, m_next;
        if (!camera_.Project(((1.0 - t) * b0 + t * b1).normalized(), &m) ||
            !camera_.Project(((0.99 - t) * b0 + (t + 0.01) * b1).normalized(), &m_next)) {
          continue;
        }
        const Vec2 tangent = (m_next - m).normalized();
        const Vec2 out(tangent.y(), -tangent.x());  // outward for clockwise-on-screen order
        const Vec2 po = m + offset * out;
        const Vec2 pi = m - offset * out;
        if (!Inside(gray_, po, 0.0) || !Inside(gray_, pi, 0.0)) continue;
        outside += Sample(gray_, po.x(), po.y());
        inside += Sample(gray_, pi.x(), pi.y());
        ++n;
      }
    }
    return n > 0 ? (outside - inside) / n : 0.0;
  }

  // Sub-pixel edge samples along the side between rough corner bearings b0, b1; polarity +1 when
  // the image gets brighter along the outward normal (outer quad), -1 otherwise.
  bool SampleSide(const Vec3& b0, const Vec3& b1, double polarity, Side* side) const {
    Vec2 p0, p1;
    if (!camera_.Project(b0, &p0) || !camera_.Project(b1, &p1)) return false;
    const double length_px = (p1 - p0).norm();
    // At least 8 (denser than edge_sample_step_px on sides under ~20 px): a far pattern's short
    // inner sides (~15 px at 5 m) need 4 samples that pass the checks below.
    const int spaced =
        static_cast<int>(length_px * (1.0 - 2.0 * p_.corner_exclusion) / p_.edge_sample_step_px);
    const int n = std::min(std::max(spaced, 8), p_.max_samples_per_side);
    const int r = p_.edge_search_px;
    std::array<double, 35> profile;  // 2 r + 3 samples, edge_search_px <= 16
    side->bearings_C.clear();
    for (int i = 0; i < n; ++i) {
      const double t = p_.corner_exclusion + (1.0 - 2.0 * p_.corner_exclusion) * (i + 0.5) / n;
      const Vec3 b = ((1.0 - t) * b0 + t * b1).normalized();
      const Vec3 bt = ((1.0 - t - 0.01) * b0 + (t + 0.01) * b1).normalized();
      Vec2 px, pxt;
      if (!camera_.Project(b, &px) || !camera_.Project(bt, &pxt)) continue;
      const Vec2 tangent = (pxt - px).normalized();
      const Vec2 out(tangent.y(), -tangent.x());
      if (!Inside(gray_, px + (r + 1) * out, 0.0) || !Inside(gray_, px - (r + 1) * out, 0.0)) continue;
      for (int s = -r - 1; s <= r + 1; ++s) {
        const Vec2 q = px + s * out;
        profile[s + r + 1] = Sample(gray_, q.x(), q.y());
      }
      // Strongest gradient of the expected polarity.
      int best = 0;
      double best_g = 0.0;
      std::array<double, 33> g{};  // edge_search_px <= 16
      for (int s = -r; s <= r; ++s) {
        g[s + r] = polarity * 0.5 * (profile[s + r + 2] - profile[s + r]);
        if (g[s + r] > best_g) {
          best_g = g[s + r];
          best = s;
        }
      }
      if (best_g < 0.25 * p_.min_contrast || best == -r || best == r) continue;
      // Sub-pixel by area: between the dark and the bright plateau, the normalized samples
      // best-1 .. best+1 sum to (best + 1.5) - edge for any pixel-area / symmetric blur inside
      // the window, so the estimate is free of the phase-dependent bias of interpolating a
      // crossing or fitting a parabola. Plateaus are the extremes of the two samples on each
      // side, so a narrow band (the white band can be ~2 px wide) does not bias the levels.
      const auto v = [&](int s) { return polarity * profile[std::clamp(s, -r - 1, r + 1) + r + 1]; };
      const double lo = std::min(v(best - 1), v(best - 2));
      const double hi = std::max(v(best + 1), v(best + 2));
      if (hi - lo < 0.5 * p_.min_contrast) continue;
      double bright = 0.0;
      for (int k = best - 1; k <= best + 1; ++k) bright += std::clamp((v(k) - lo) / (hi - lo), 0.0, 1.0);
      const double delta = 1.5 - bright;
      const Vec2 edge_px = px + (best + delta) * out;
      side->bearings_C.push_back(camera_.Unproject(edge_px));
    }
    if (side->bearings_C.size() < 4) return false;
    Mat3 scatter = Mat3::Zero();
    for (const Vec3& b : side->bearings_C) scatter += b * b.transpose();
    Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter);
    side->normal_C = eig.eigenvectors().col(0);
    return true;
  }

  // Edge normals of the 8 model sides for pose (R, t): side k of quad q joins model corners
  // 4q+k and 4q+(k+1)%4. Also d(normal)/d(delta) for delta = [dt; dr] (left perturbation).
  void ModelNormals(const Mat3& R, const Vec3& t, std::array<Vec3, 8>* n,
                    std::array<Eigen::Matrix<double, 3, 6>, 8>* dn) const {
    for (int q = 0; q < 2; ++q) {
      for (int k = 0; k < 4; ++k) {
        const Vec3 A = R * model_G_[4 * q + k] + t;
        const Vec3 B = R * model_G_[4 * q + (k + 1) % 4] + t;
        const Vec3 m = A.cross(B);
        const double norm = m.norm();
        const Vec3 nh = m / norm;
        (*n)[4 * q + k] = nh;
        if (dn) {
          Eigen::Matrix<double, 3, 6> dA, dB;
          dA << Mat3::Identity(), -Skew(A);
          dB << Mat3::Identity(), -Skew(B);
          const Eigen::Matrix<double, 3, 6> dm = -Skew(B) * dA + Skew(A) * dB;
          (*dn)[4 * q + k] = (Mat3::Identity() - nh * nh.transpose()) / norm * dm;
        }
      }
    }
  }

  // Pixels per radian off the plane through C with normal n, at bearing b (through the camera
  // model); 0 where b does not project.
  double PixelsPerRadianOffPlane(const Vec3& n, const Vec3& b) const {
    const Vec3 u = n - n.dot(b) * b;
    Vec2 px;
    Eigen::Matrix<double, 2, 3> J;
    if (u.norm() < 1e-9 || !camera_.Project(b, &px, &J)) return 0.0;
    return (J * u.normalized()).norm();
  }

  // Drops the edge samples farther than 3 pixel_sigma_px from the edges of pose (R, t): samples
  // that latched onto a neighbouring edge (the far side of a ~2 px white band, the panel's
  // border) bias a far pattern's pose by degrees. Returns the number dropped.
  int DropOutlierSamples(const Mat3& R, const Vec3& t, std::array<Side, 8>* sides) const {
    std::array<Vec3, 8> n;
    ModelNormals(R, t, &n, nullptr);
    const double max_px = 3.0 * p_.pixel_sigma_px;
    int dropped = 0;
    for (int e = 0; e < 8; ++e) {
      std::vector<Vec3>& bearings = (*sides)[e].bearings_C;
      const auto end = std::remove_if(bearings.begin(), bearings.end(), [&](const Vec3& b) {
        return std::abs(PixelsPerRadianOffPlane(n[e], b) * n[e].dot(b)) > max_px;
      });
      dropped += static_cast<int>(bearings.end() - end);
      bearings.erase(end, bearings.end());
    }
    return dropped;
  }

  // Gauss-Newton on SE(3) minimizing the pixel distances of all edge samples to the projected
  // model edges (bearing-to-plane residual scaled to pixels). Returns false on degeneracy.
  bool Refine(const std::array<Side, 8>& sides, Mat3* R, Vec3* t, GapDetection* out) const {
    std::array<Vec3, 8> n;
    std::array<Eigen::Matrix<double, 3, 6>, 8> dn;
    ModelNormals(*R, *t, &n, nullptr);
    // Residual of sample i on edge e: r_i = f_i * n_e . b_i (sine of the angle between the
    // sample's bearing and the plane through C and the model edge, times f_i = pixels per radian
    // off that plane through the camera model; weights fixed at the start pose). The sum of
    // squares per edge collapses to n_e^T M_e n_e with M_e = sum f_i^2 b_i b_i^T.
    std::array<Mat3, 8> M;
    int samples = 0;
    for (int e = 0; e < 8; ++e) {
      M[e].setZero();
      for (const Vec3& b : sides[e].bearings_C) {
        const double f = PixelsPerRadianOffPlane(n[e], b);
        if (f <= 0.0) continue;
        M[e] += f * f * b * b.transpose();
        ++samples;
      }
    }
    Mat6 H = Mat6::Zero();
    for (int it = 0; it <= p_.refinement_iterations; ++it) {
      ModelNormals(*R, *t, &n, &dn);
      H.setZero();
      Vec6 g = Vec6::Zero();
      for (int e = 0; e < 8; ++e) {
        H += dn[e].transpose() * M[e] * dn[e];
        g += dn[e].transpose() * M[e] * n[e];
      }
      if (it == p_.refinement_iterations) break;
      const Vec6 delta = -H.ldlt().solve(g);
      if (!delta.allFinite()) return false;
      const Mat3 dR = control::ExpSo3(delta.tail<3>());
      *R = dR * *R;
      *t = dR * *t + delta.head<3>();
      if (delta.norm() < 1e-10) {
        ModelNormals(*R, *t, &n, &dn);
        H.setZero();
        for (int e = 0; e < 8; ++e) H += dn[e].transpose() * M[e] * dn[e];
        break;
      }
    }
    double cost = 0.0;
    for (int e = 0; e < 8; ++e) cost += n[e].dot(M[e] * n[e]);
    Eigen::FullPivLU<Mat6> lu(H);
    if (!lu.isInvertible()) return false;
    out->covariance = p_.pixel_sigma_px * p_.pixel_sigma_px * lu.inverse();
    out->edge_samples = samples;
    out->edge_rms_px = samples > 0 ? std::sqrt(cost / samples) : 0.0;
    return true;
  }

  // Full pipeline from a nested pair of rough quads. Corners of both are in positive order.
  // The model's long side (x_G) goes to the pair of opposite sides that looks longer in the
  // image; seen more than ~53 deg off the normal across its long side (1.3 x 0.78 m: cos < 0.6)
  // the pattern's short side looks longer, so the other labelling is tried when the first fails
  // the checks (its corners are then ~10 px off the 8-corner PnP).
  GapDetection Solve(const Quad& outer, const Quad& inner) const {
    const GapDetection d = SolveLabelled(outer, inner, /*long_side_looks_shorter=*/false);
    return d.detected() ? d : SolveLabelled(outer, inner, /*long_side_looks_shorter=*/true);
  }

  GapDetection SolveLabelled(Quad outer, Quad inner, bool long_side_looks_shorter) const {
    GapDetection result;
    result.status = GapDetectionStatus::kReprojectionRejected;
    // Virtual camera at the pattern; long side first (model side 0 is along x_G).
    const Mat3 R_VC = VirtualCameraRotation(outer.bearing_C[0] + outer.bearing_C[1] +
                                            outer.bearing_C[2] + outer.bearing_C[3]);
    std::array<Vec2, 4> uo, ui;
    for (int k = 0; k < 4; ++k) {
      if (!Gnomonic(R_VC * outer.bearing_C[k], &uo[k]) || !Gnomonic(R_VC * inner.bearing_C[k], &ui[k]))
        return result;
    }
    const double along_first = (uo[1] - uo[0]).norm() + (uo[3] - uo[2]).norm();
    const double along_second = (uo[2] - uo[1]).norm() + (uo[0] - uo[3]).norm();
    const int shift = (along_first >= along_second) != long_side_looks_shorter ? 0 : 1;
    std::rotate(outer.bearing_C.begin(), outer.bearing_C.begin() + shift, outer.bearing_C.end());
    std::rotate(outer.px.begin(), outer.px.begin() + shift, outer.px.end());
    std::rotate(uo.begin(), uo.begin() + shift, uo.end());
    // Inner corner k: the inner corner nearest to outer corner k.
    int inner_shift = 0;
    double best = 1e300;
    for (int s = 0; s < 4; ++s) {
      double d = 0.0;
      for (int k = 0; k < 4; ++k) d += (ui[(k + s) % 4] - uo[k]).squaredNorm();
      if (d < best) {
        best = d;
        inner_shift = s;
      }
    }
    std::rotate(inner.bearing_C.begin(), inner.bearing_C.begin() + inner_shift, inner.bearing_C.end());

    // Sub-pixel edges and corners by line (great circle) intersection.
    std::array<Side, 8> sides;
    for (int q = 0; q < 2; ++q) {
      const Quad& quad = q == 0 ? outer : inner;
      const double polarity = q == 0 ? 1.0 : -1.0;
      for (int k = 0; k < 4; ++k) {
        if (!SampleSide(quad.bearing_C[k], quad.bearing_C[(k + 1) % 4], polarity, &sides[4 * q + k]))
          return result;
      }
    }
    std::array<Vec3, 8> corner_C;
    for (int q = 0; q < 2; ++q) {
      const Quad& quad = q == 0 ? outer : inner;
      for (int k = 0; k < 4; ++k) {
        Vec3 c = sides[4 * q + (k + 3) % 4].normal_C.cross(sides[4 * q + k].normal_C);
        if (c.norm() < 1e-9) return result;
        c.normalize();
        if (c.dot(quad.bearing_C[k]) < 0.0) c = -c;
        corner_C[4 * q + k] = c;
      }
    }
    // PnP (n = 8) on gnomonic coordinates of the virtual camera: valid for any lens.
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (int i = 0; i < 8; ++i) {
      Vec2 u;
      if (!Gnomonic(R_VC * corner_C[i], &u)) return result;
      object.emplace_back(model_G_[i].x(), model_G_[i].y(), model_G_[i].z());
      image.emplace_back(u.x(), u.y());
    }
    cv::Mat rvec, tvec;
    if (!cv::solvePnP(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec, false,
                      cv::SOLVEPNP_IPPE)) {
      return result;
    }
    cv::Mat R_cv;
    cv::Rodrigues(rvec, R_cv);
    Mat3 R_VG;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R_VG(r, c) = R_cv.at<double>(r, c);
    const Vec3 t_VG(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
    Mat3 R = R_VC.transpose() * R_VG;
    Vec3 t = R_VC.transpose() * t_VG;
    if (t.norm() <= 0.0 || !R.allFinite()) return result;

    std::array<Vec2, 8> corner_px;
    for (int i = 0; i < 8; ++i) {
      if (!camera_.Project(corner_C[i], &corner_px[i])) return result;
    }
    auto corner_rms = [&](const Mat3& Rc, const Vec3& tc, double* rms) {
      double sum = 0.0;
      for (int i = 0; i < 8; ++i) {
        Vec2 px;
        if (!camera_.Project(Rc * model_G_[i] + tc, &px)) return false;
        sum += (px - corner_px[i]).squaredNorm();
      }
      *rms = std::sqrt(sum / 8.0);
      return true;
    };
    double rms = 0.0;
    if (!corner_rms(R, t, &rms) || rms > p_.max_corner_rms_px) return result;

    if (!Refine(sides, &R, &t, &result)) return result;
    // Up to three rounds of dropping the samples off the refined edges and refining again.
    for (int round = 0; round < 3 && DropOutlierSamples(R, t, &sides) > 0; ++round) {
      if (!Refine(sides, &R, &t, &result)) return result;
    }
    if (!corner_rms(R, t, &rms) || rms > p_.max_corner_rms_px) return result;

    // Symmetry convention: x_G towards the image's right half-plane. Rz(pi) maps model corner k
    // to k+2 of the same quad and is an exact symmetry, so only the labels change.
    std::array<Vec2, 8> labelled = corner_px;
    if (R(0, 0) < 0.0) {
      R = R * Eigen::AngleAxisd(M_PI, Vec3::UnitZ()).toRotationMatrix();
      for (int i = 0; i < 8; ++i) labelled[i] = corner_px[(i / 4) * 4 + (i % 4 + 2) % 4];
    }
    result.status = GapDetectionStatus::kDetected;
    result.T_CG.linear() = R;
    result.T_CG.translation() = t;
    result.corner_rms_px = rms;
    result.corners_px.assign(labelled.begin(), labelled.end());
    return result;
  }

 private:
  const GapDetectorParams& p_;
  const CameraModel& camera_;
  const cv::Mat& gray_;
  std::vector<Vec3> model_G_;
};

}  // namespace

GapDetection GapDetector::DetectIn(const cv::Mat& gray, const cv::Rect& roi) {
  Impl& im = *impl_;
  // Canny edges dilated by one pixel to close one-pixel breaks (corners), so each pattern edge
  // gives a closed contour.
  im.canny.Detect(gray, roi, params_.canny_low, params_.canny_high, /*dilate_3x3=*/true, &im.edges);
  im.contours.clear();
  cv::findContours(im.edges, im.contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE, roi.tl());

  Attempt attempt(params_, *camera_, gray, ModelCorners());
  const double focal = camera_->intrinsics()[0];
  std::vector<Quad> outers, inners;
  for (const auto& contour : im.contours) {
    // A closed chain of n 8-connected steps is n to sqrt(2) n long: arcLength only in between.
    const double steps = static_cast<double>(contour.size());
    if (steps * std::sqrt(2.0) < params_.min_perimeter_px ||
        (steps < params_.min_perimeter_px && cv::arcLength(contour, true) < params_.min_perimeter_px)) {
      continue;
    }
    Vec3 mean = Vec3::Zero();
    for (const cv::Point& p : contour) mean += im.TableBearing(p);
    if (mean.norm() < 1e-6) continue;
    const Mat3 R_VC = VirtualCameraRotation(mean);
    im.gnomonic.clear();
    bool ok = true;
    for (const cv::Point& p : contour) {
      Vec2 u;
      if (!Gnomonic(R_VC * im.TableBearing(p), &u)) {
        ok = false;
        break;
      }
      im.gnomonic.emplace_back(static_cast<float>(focal * u.x()), static_cast<float>(focal * u.y()));
    }
    if (!ok) continue;
    const double perimeter = cv::arcLength(im.gnomonic, true);
    cv::approxPolyDP(im.gnomonic, im.polygon, params_.approx_epsilon_ratio * perimeter, true);
    for (double ratio = params_.approx_epsilon_ratio;
         im.polygon.size() > 4 && cv::isContourConvex(im.polygon) &&
         ratio < params_.approx_epsilon_max_ratio;) {
      ratio = std::min(1.6 * ratio, params_.approx_epsilon_max_ratio);
      cv::approxPolyDP(im.gnomonic, im.polygon, ratio * perimeter, true);
    }
    if (im.polygon.size() != 4 || !cv::isContourConvex(im.polygon)) continue;
    std::array<Vec2, 4> g;
    for (int k = 0; k < 4; ++k) g[k] = Vec2(im.polygon[k].x, im.polygon[k].y);
    if (SignedArea(g) < 0.0) std::reverse(g.begin(), g.end());
    Quad quad;
    bool projectable = true;
    double min_side = 1e300;
    for (int k = 0; k < 4; ++k) {
      quad.bearing_C[k] = (R_VC.transpose() * Vec3(g[k].x() / focal, g[k].y() / focal, 1.0)).normalized();
      projectable = projectable && camera_->Project(quad.bearing_C[k], &quad.px[k]);
    }
    if (!projectable) continue;
    for (int k = 0; k < 4; ++k) min_side = std::min(min_side, (quad.px[(k + 1) % 4] - quad.px[k]).norm());
    if (min_side < params_.min_side_px) continue;
    quad.contrast = attempt.Contrast(quad);
    if (quad.contrast >= params_.min_contrast) outers.push_back(quad);
    if (quad.contrast <= -params_.min_contrast) inners.push_back(quad);
  }

  // Nested pairs with the expected area ratio, best ratio first.
  const double expected_ratio = params_.outer_size_m.prod() / params_.inner_size_m.prod();
  struct Pair {
    double score;
    int outer;
    int inner;
  };
  std::vector<Pair> pairs;
  for (size_t o = 0; o < outers.size(); ++o) {
    const Mat3 R_VC = VirtualCameraRotation(outers[o].bearing_C[0] + outers[o].bearing_C[1] +
                                            outers[o].bearing_C[2] + outers[o].bearing_C[3]);
    std::array<Vec2, 4> uo;
    bool ok = true;
    for (int k = 0; k < 4; ++k) ok = ok && Gnomonic(R_VC * outers[o].bearing_C[k], &uo[k]);
    if (!ok) continue;
    const double area_outer = SignedArea(uo);
    for (size_t i = 0; i < inners.size(); ++i) {
      std::array<Vec2, 4> ui;
      bool in_front = true;
      for (int k = 0; k < 4; ++k) in_front = in_front && Gnomonic(R_VC * inners[i].bearing_C[k], &ui[k]);
      if (!in_front) continue;
      bool contained = true;
      for (int k = 0; k < 4 && contained; ++k) {
        for (int s = 0; s < 4; ++s) {
          const Vec2 e = uo[(s + 1) % 4] - uo[s];
          const Vec2 d = ui[k] - uo[s];
          if (e.x() * d.y() - e.y() * d.x() <= 0.0) {
            contained = false;
            break;
          }
        }
      }
      if (!contained) continue;
      const double ratio = area_outer / SignedArea(ui);
      const double score = std::abs(std::log(ratio / expected_ratio));
      if (score > std::log(params_.area_ratio_tolerance)) continue;
      pairs.push_back({score, static_cast<int>(o), static_cast<int>(i)});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.score < b.score; });

  GapDetection result;
  result.status = GapDetectionStatus::kNoCandidate;
  constexpr int kMaxPairsTried = 8;  // duplicates of one pattern (both sides of each edge) come first
  for (int k = 0; k < static_cast<int>(pairs.size()) && k < kMaxPairsTried; ++k) {
    GapDetection d = attempt.Solve(outers[pairs[k].outer], inners[pairs[k].inner]);
    if (d.detected()) return d;
    result.status = d.status;
  }
  return result;
}

const cv::Mat& GapDetector::ToGray(const cv::Mat& image) {
  if (image.empty() || image.cols != camera_->width() || image.rows != camera_->height() ||
      (image.type() != CV_8UC1 && image.type() != CV_8UC3)) {
    std::ostringstream s;
    s << "GapDetector: image is " << image.cols << "x" << image.rows << " type " << image.type()
      << "; expected CV_8UC1 or CV_8UC3 of the camera's " << camera_->width() << "x"
      << camera_->height() << " (check the calibration matches the frames)";
    throw std::invalid_argument(s.str());
  }
  if (image.type() == CV_8UC1) return image;
  cv::cvtColor(image, impl_->gray, cv::COLOR_BGR2GRAY);
  return impl_->gray;
}

GapDetection GapDetector::DetectFullImage(const cv::Mat& image) {
  return DetectIn(ToGray(image), cv::Rect(0, 0, image.cols, image.rows));
}

GapDetection GapDetector::Detect(const cv::Mat& image) {
  const cv::Mat& gray = ToGray(image);
  if (params_.use_roi && has_last_) {
    // ROI from the last detection's projected outer corners.
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    bool ok = true;
    const std::vector<Vec3> model = ModelCorners();
    for (int k = 0; k < 4 && ok; ++k) {
      Vec2 px;
      ok = camera_->Project(last_T_CG_ * model[k], &px);
      x0 = std::min(x0, px.x());
      y0 = std::min(y0, px.y());
      x1 = std::max(x1, px.x());
      y1 = std::max(y1, px.y());
    }
    if (ok) {
      const double mx = params_.roi_margin_ratio * (x1 - x0) + params_.roi_margin_px;
      const double my = params_.roi_margin_ratio * (y1 - y0) + params_.roi_margin_px;
      const cv::Rect roi = cv::Rect(cv::Point(static_cast<int>(std::floor(x0 - mx)), static_cast<int>(std::floor(y0 - my))),
                                    cv::Point(static_cast<int>(std::ceil(x1 + mx)), static_cast<int>(std::ceil(y1 + my)))) &
                           cv::Rect(0, 0, camera_->width(), camera_->height());
      if (roi.width > 8 && roi.height > 8) {
        GapDetection d = DetectIn(gray, roi);
        if (d.detected()) {
          d.from_roi = true;
          last_T_CG_ = d.T_CG;
          return d;
        }
      }
    }
  }
  GapDetection d = DetectIn(gray, cv::Rect(0, 0, gray.cols, gray.rows));
  has_last_ = d.detected();
  if (has_last_) last_T_CG_ = d.T_CG;
  return d;
}

}  // namespace aperture::perception
