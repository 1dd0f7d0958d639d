// Camera models: round trips, analytic vs numeric Jacobians, agreement with OpenCV's projection
// functions, resampling, validity limits and factory validation.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/camera/camera_factory.h"
#include "perception/camera/equidistant_camera.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/camera/radtan_camera.h"

namespace aperture::perception {
namespace {

struct CameraCase {
  std::string label;
  std::string model;
  int width;
  int height;
  std::vector<double> intrinsics;  // fx fy cx cy
  std::vector<double> distortion;
};

std::ostream& operator<<(std::ostream& os, const CameraCase& c) { return os << c.label; }

Eigen::VectorXd ToEigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::unique_ptr<CameraModel> Make(const CameraCase& c) {
  return CreateCameraModel(c.model, c.width, c.height, ToEigen(c.intrinsics),
                           ToEigen(c.distortion));
}

// Angle of a bearing off the optical axis [rad].
double OffAxisAngle(const Eigen::Vector3d& b) { return std::atan2(b.head<2>().norm(), b.z()); }

class CameraModelTest : public ::testing::TestWithParam<CameraCase> {
 protected:
  void SetUp() override { camera_ = Make(GetParam()); }
  std::unique_ptr<CameraModel> camera_;
};

// Every pixel of the image (2 px grid plus the outer pixel edges) unprojects to a unit bearing
// that projects back onto the same pixel. 1e-9 px is the required convergence of the iterative
// undistortion; the remaining error is floating point rounding (~1e-12 px).
TEST_P(CameraModelTest, UnprojectThenProjectRoundTripsOverWholeImage) {
  const CameraModel& cam = *camera_;
  std::vector<double> us, vs;
  for (double u = -0.5; u < cam.width() - 0.5; u += 2.0) us.push_back(u);
  us.push_back(cam.width() - 0.5);
  for (double v = -0.5; v < cam.height() - 0.5; v += 2.0) vs.push_back(v);
  vs.push_back(cam.height() - 0.5);
  double max_error_px = 0.0, max_angle_rad = 0.0;
  for (double u : us) {
    for (double v : vs) {
      const Eigen::Vector2d px(u, v);
      const Eigen::Vector3d bearing = cam.Unproject(px);
      ASSERT_NEAR(bearing.norm(), 1.0, 1e-12);
      Eigen::Vector2d px_back;
      ASSERT_TRUE(cam.Project(bearing, &px_back)) << "pixel " << px.transpose();
      max_error_px = std::max(max_error_px, (px_back - px).norm());
      max_angle_rad = std::max(max_angle_rad, OffAxisAngle(bearing));
    }
  }
  EXPECT_LT(max_error_px, 1e-9);
  RecordProperty("max_round_trip_error_px", std::to_string(max_error_px));
  std::cout << GetParam().label << ": max round-trip error " << max_error_px
            << " px, max off-axis angle " << max_angle_rad * 180.0 / M_PI << " deg\n";
}

// Points at random depths along random in-image rays. Central differences with step
// h = 1e-6 |p| have truncation error O(h^2) ~ 1e-12 relative and rounding error
// ~ 1e-16 |px| / h ~ 1e-7 px/m for |px| ~ 1e3, |p| ~ 1: tolerance 1e-5 relative to max |J|.
TEST_P(CameraModelTest, JacobianMatchesCentralDifferences) {
  const CameraModel& cam = *camera_;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u_dist(0.0, cam.width() - 1.0);
  std::uniform_real_distribution<double> v_dist(0.0, cam.height() - 1.0);
  std::uniform_real_distribution<double> depth_dist(0.3, 10.0);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d p_C =
        depth_dist(rng) * cam.Unproject(Eigen::Vector2d(u_dist(rng), v_dist(rng)));
    Eigen::Vector2d px;
    Eigen::Matrix<double, 2, 3> J;
    ASSERT_TRUE(cam.Project(p_C, &px, &J));
    Eigen::Matrix<double, 2, 3> J_numeric;
    const double h = 1e-6 * p_C.norm();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d px_plus, px_minus;
      ASSERT_TRUE(cam.Project(p_C + h * Eigen::Vector3d::Unit(k), &px_plus));
      ASSERT_TRUE(cam.Project(p_C - h * Eigen::Vector3d::Unit(k), &px_minus));
      J_numeric.col(k) = (px_plus - px_minus) / (2.0 * h);
    }
    EXPECT_LT((J - J_numeric).cwiseAbs().maxCoeff(), 1e-5 * J.cwiseAbs().maxCoeff())
        << "p_C " << p_C.transpose() << "\nJ\n"
        << J << "\nnumeric\n"
        << J_numeric;
  }
}

// Points on the optical axis use the pinhole limit of the model; its Jacobian must also hold.
TEST_P(CameraModelTest, ProjectsTheOpticalAxisToThePrincipalPoint) {
  const Eigen::Vector4d k = camera_->intrinsics();
  Eigen::Vector2d px;
  Eigen::Matrix<double, 2, 3> J;
  ASSERT_TRUE(camera_->Project(Eigen::Vector3d(0, 0, 2.0), &px, &J));
  EXPECT_NEAR((px - k.tail<2>()).norm(), 0.0, 1e-12);
  Eigen::Matrix<double, 2, 3> J_expected;
  J_expected << k[0] / 2.0, 0, 0, 0, k[1] / 2.0, 0;
  EXPECT_LT((J - J_expected).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_FALSE(camera_->Project(Eigen::Vector3d::Zero(), &px));
}

// Our projection equals OpenCV's for points in front of the camera (equidistant: OpenCV's fisheye
// formulation via atan(r) only covers theta < 90 deg). Both evaluate the same polynomial in
// double precision: 1e-6 px leaves room for the different evaluation order only.
TEST_P(CameraModelTest, MatchesOpenCvProjection) {
  const CameraModel& cam = *camera_;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u_dist(0.0, cam.width() - 1.0);
  std::uniform_real_distribution<double> v_dist(0.0, cam.height() - 1.0);
  std::uniform_real_distribution<double> depth_dist(0.3, 10.0);
  std::vector<cv::Point3d> points;
  std::vector<Eigen::Vector2d> ours;
  while (points.size() < 400) {
    const Eigen::Vector3d p_C =
        depth_dist(rng) * cam.Unproject(Eigen::Vector2d(u_dist(rng), v_dist(rng)));
    if (p_C.z() <= 1e-3 * p_C.norm()) continue;
    Eigen::Vector2d px;
    ASSERT_TRUE(cam.Project(p_C, &px));
    points.emplace_back(p_C.x(), p_C.y(), p_C.z());
    ours.push_back(px);
  }
  const Eigen::Vector4d k = cam.intrinsics();
  const cv::Matx33d K(k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1);
  const Eigen::VectorXd d = cam.distortion();
  std::vector<double> coefficients(d.data(), d.data() + d.size());
  std::vector<cv::Point2d> theirs;
  if (cam.model_name() == "equidistant") {
    cv::fisheye::projectPoints(points, theirs, cv::Vec3d::all(0), cv::Vec3d::all(0), K,
                               coefficients);
  } else {
    cv::projectPoints(points, cv::Vec3d::all(0), cv::Vec3d::all(0), K, coefficients, theirs);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(ours[i].x(), theirs[i].x, 1e-6);
    EXPECT_NEAR(ours[i].y(), theirs[i].y, 1e-6);
  }
}

// Resampling the image by s maps pixel centres as u' = (u + 0.5) s - 0.5 (pixel-centre
// convention). Exact up to rounding: 1e-9 px.
TEST_P(CameraModelTest, ScaledModelEqualsScaledPixels) {
  const CameraModel& cam = *camera_;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u_dist(0.0, cam.width() - 1.0);
  std::uniform_real_distribution<double> v_dist(0.0, cam.height() - 1.0);
  const std::vector<std::pair<int, int>> sizes = {{cam.width() / 2, cam.height() / 2},
                                                  {cam.width() * 3 / 2, cam.height()},
                                                  {cam.width() * 2, cam.height() * 2}};
  for (const auto& [w, h] : sizes) {
    const std::unique_ptr<CameraModel> scaled = cam.Scaled(w, h);
    ASSERT_EQ(scaled->width(), w);
    ASSERT_EQ(scaled->height(), h);
    EXPECT_EQ(scaled->model_name(), cam.model_name());
    EXPECT_EQ(scaled->distortion(), cam.distortion());
    const double sx = static_cast<double>(w) / cam.width();
    const double sy = static_cast<double>(h) / cam.height();
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d p_C = cam.Unproject(Eigen::Vector2d(u_dist(rng), v_dist(rng)));
      Eigen::Vector2d px, px_scaled;
      ASSERT_TRUE(cam.Project(p_C, &px));
      ASSERT_TRUE(scaled->Project(p_C, &px_scaled));
      EXPECT_NEAR(px_scaled.x(), (px.x() + 0.5) * sx - 0.5, 1e-9);
      EXPECT_NEAR(px_scaled.y(), (px.y() + 0.5) * sy - 0.5, 1e-9);
    }
  }
}

TEST_P(CameraModelTest, CloneProjectsIdentically) {
  const std::unique_ptr<CameraModel> clone = camera_->Clone();
  EXPECT_EQ(clone->model_name(), camera_->model_name());
  EXPECT_EQ(clone->intrinsics(), camera_->intrinsics());
  EXPECT_EQ(clone->distortion(), camera_->distortion());
  const Eigen::Vector3d p_C(0.1, -0.2, 1.5);
  Eigen::Vector2d a, b;
  ASSERT_TRUE(camera_->Project(p_C, &a));
  ASSERT_TRUE(clone->Project(p_C, &b));
  EXPECT_EQ(a, b);
}

INSTANTIATE_TEST_SUITE_P(
    Models, CameraModelTest,
    ::testing::Values(
        CameraCase{"pinhole_vga", "pinhole", 640, 480, {500.0, 505.0, 319.5, 239.5}, {}},
        // EuRoC MAV cam0 (Kalibr radtan).
        CameraCase{"radtan_euroc",
                   "radtan",
                   752,
                   480,
                   {458.654, 457.296, 367.215, 248.375},
                   {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}},
        CameraCase{"radtan_k3",
                   "radtan",
                   640,
                   480,
                   {600.0, 602.0, 322.0, 241.0},
                   {-0.35, 0.15, 0.001, -0.0005, -0.03}},
        // Intel T265-like fisheye (Kalibr equidistant).
        CameraCase{"equidistant_t265",
                   "equidistant",
                   848,
                   800,
                   {286.18, 286.39, 416.94, 403.62},
                   {-0.0102, 0.0471, -0.0444, 0.0083}},
        // 180 deg lens: theta_d(90 deg) * f = 213 px < 240 px, so 90 deg is inside the image.
        CameraCase{"equidistant_180deg",
                   "equidistant",
                   752,
                   480,
                   {140.0, 140.0, 375.5, 239.5},
                   {-0.02, 0.003, 0.0, 0.0}}),
    [](const ::testing::TestParamInfo<CameraCase>& info) { return info.param.label; });

TEST(EquidistantCameraTest, ProjectsBeyondNinetyDegreesOffAxis) {
  const EquidistantCamera cam(752, 480, {140.0, 140.0, 375.5, 239.5}, {-0.02, 0.003, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(cam.max_valid_angle(), M_PI);  // theta_d' = 1 - 0.06 t^2 + 0.015 t^4 > 0
  for (double angle_deg : {60.0, 90.0, 100.0, 120.0}) {
    const double a = angle_deg * M_PI / 180.0;
    const Eigen::Vector3d p_C(std::sin(a), 0.0, std::cos(a));
    Eigen::Vector2d px;
    ASSERT_TRUE(cam.Project(p_C, &px)) << angle_deg;
    // Pure equidistant geometry along +x: u = cx + f theta_d(theta).
    EXPECT_NEAR(px.x(), 375.5 + 140.0 * cam.DistortAngle(a), 1e-9);
    EXPECT_NEAR(px.y(), 239.5, 1e-12);
    EXPECT_NEAR(OffAxisAngle(cam.Unproject(px)), a, 1e-12);
  }
  Eigen::Vector2d px;
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(0.0, 0.0, -1.0), &px));  // straight behind
}

// Just off the optical axis the general formula (theta_d / rho) takes over from the pinhole
// limit used on the axis; both sides must agree with the first-order model f/Z (relative
// corrections are O(theta^2) < 1e-12 here).
TEST(EquidistantCameraTest, JacobianIsContinuousAcrossTheAxisSpecialCase) {
  const EquidistantCamera cam(752, 480, {140.0, 141.0, 375.5, 239.5}, {-0.02, 0.003, 0.01, 0.0});
  const double z = 2.0;
  Eigen::Matrix<double, 2, 3> J_axis;
  J_axis << 140.0 / z, 0, 0, 0, 141.0 / z, 0;
  for (double rho_over_z : {1e-10, 1e-8 * 0.999, 1e-8 * 1.001, 1e-7}) {
    const Eigen::Vector3d p_C(0.6 * rho_over_z * z, -0.8 * rho_over_z * z, z);
    Eigen::Vector2d px;
    Eigen::Matrix<double, 2, 3> J;
    ASSERT_TRUE(cam.Project(p_C, &px, &J));
    EXPECT_LT((J.leftCols<2>() - J_axis.leftCols<2>()).cwiseAbs().maxCoeff(), 1e-9) << J;
    // d px / dZ = -f X / Z^2 to first order.
    EXPECT_NEAR(J(0, 2), -140.0 * p_C.x() / (z * z), 1e-9);
    EXPECT_NEAR(px.x(), 375.5 + 140.0 * p_C.x() / z, 1e-9);
  }
}

TEST(EquidistantCameraTest, ValidAngleEndsWhereThetaDStopsIncreasing) {
  // theta_d = theta - 0.1 theta^3: d/dtheta = 1 - 0.3 theta^2 = 0 at theta = sqrt(1/0.3).
  const EquidistantCamera cam(640, 480, {200.0, 200.0, 320.0, 240.0}, {-0.1, 0.0, 0.0, 0.0});
  EXPECT_NEAR(cam.max_valid_angle(), std::sqrt(1.0 / 0.3), 1e-12);
  Eigen::Vector2d px;
  const double inside = cam.max_valid_angle() - 1e-3, outside = cam.max_valid_angle() + 1e-3;
  EXPECT_TRUE(cam.Project(Eigen::Vector3d(std::sin(inside), 0, std::cos(inside)), &px));
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(std::sin(outside), 0, std::cos(outside)), &px));
  // A pixel beyond the valid image circle maps to a ray at the valid angle.
  EXPECT_NEAR(OffAxisAngle(cam.Unproject(Eigen::Vector2d(639.0, 240.0))), cam.max_valid_angle(),
              1e-12);
}

TEST(RadTanCameraTest, RejectsPointsBeyondTheFold) {
  // x_d = r (1 - 0.3 r^2) folds at 1 - 0.9 r^2 = 0.
  const RadTanCamera cam(640, 480, {300.0, 300.0, 320.0, 240.0}, {-0.3, 0.0, 0.0, 0.0, 0.0, false});
  EXPECT_NEAR(cam.max_valid_radius(), std::sqrt(1.0 / 0.9), 1e-12);
  Eigen::Vector2d px;
  EXPECT_TRUE(cam.Project(Eigen::Vector3d(1.0, 0.0, 1.0), &px));
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(1.1, 0.0, 1.0), &px));
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(0.1, 0.0, -1.0), &px));
}

TEST(PinholeCameraTest, RejectsPointsBehindTheCamera) {
  const PinholeCamera cam(640, 480, {500.0, 500.0, 320.0, 240.0});
  Eigen::Vector2d px(1.0, 2.0);
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(0.1, 0.1, -1.0), &px));
  EXPECT_EQ(px, Eigen::Vector2d(1.0, 2.0));  // untouched
  EXPECT_TRUE(cam.IsInImage({-0.5, -0.5}));
  EXPECT_FALSE(cam.IsInImage({-0.6, 10.0}));
  EXPECT_FALSE(cam.IsInImage({5.0, 5.0}, 6.0));
}

void ExpectFactoryError(const std::string& model, int w, int h, const std::vector<double>& k,
                        const std::vector<double>& d, const std::string& field) {
  try {
    CreateCameraModel(model, w, h, ToEigen(k), ToEigen(d));
    ADD_FAILURE() << "no error for field " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(CameraFactoryTest, ValidatesEveryField) {
  const std::vector<double> k = {500, 500, 320, 240};
  ExpectFactoryError("fisheye_ds", 640, 480, k, {}, "model");
  ExpectFactoryError("pinhole", 0, 480, k, {}, "width");
  ExpectFactoryError("pinhole", 640, -1, k, {}, "height");
  ExpectFactoryError("pinhole", 640, 480, {500, 500, 320}, {}, "intrinsics");
  ExpectFactoryError("pinhole", 640, 480, {0, 500, 320, 240}, {}, "fx");
  ExpectFactoryError("pinhole", 640, 480, {500, NAN, 320, 240}, {}, "fy");
  ExpectFactoryError("pinhole", 640, 480, {500, 500, INFINITY, 240}, {}, "cx");
  ExpectFactoryError("pinhole", 640, 480, k, {0.1}, "distortion");
  ExpectFactoryError("radtan", 640, 480, k, {0.1, 0.0, 0.0}, "distortion");
  ExpectFactoryError("radtan", 640, 480, k, {0.1, 0.0, 0.0, 0.0, 0.0, 0.0}, "distortion");
  ExpectFactoryError("radtan", 640, 480, k, {0.1, NAN, 0.0, 0.0}, "k2");
  ExpectFactoryError("equidistant", 640, 480, k, {0.1, 0.0, 0.0, 0.0, 0.0}, "distortion");
  ExpectFactoryError("equidistant", 640, 480, k, {0.1, 0.0, 0.0, INFINITY}, "k4");
}

}  // namespace
}  // namespace aperture::perception
