#include "apps/chase_view.h"

#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "perception/camera/optical_axes.h"
#include "sim/render/camera_effects.h"

namespace aperture::apps {
namespace {

// The marker waits here between renders: far below the ground, outside every view.
Eigen::Isometry3d ParkingPose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.0, 0.0, -1000.0);
  return T;
}

perception::PinholeCamera MakeCamera(int height) {
  const int width = height * 4 / 3;
  const double focal_px = 0.5 * width / std::tan(35.0 * M_PI / 180.0);  // 70 deg FOV
  return perception::PinholeCamera(
      width, height,
      perception::PinholeIntrinsics{focal_px, focal_px, 0.5 * (width - 1), 0.5 * (height - 1)});
}

int ValidatedHeight(const ChaseViewParams& params) {
  params.Validate();
  return params.render_height;
}

Eigen::Isometry3d ChaseCameraPose(const control::QuadState& state) {
  const Eigen::Vector3d x_B = state.q_WB * Eigen::Vector3d::UnitX();
  const double yaw = std::atan2(x_B.y(), x_B.x());
  const Eigen::Matrix3d R_WH = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // C (x right, y down, z forward) in the heading frame H (x forward, y left, z up), pitched down.
  Eigen::Matrix3d R_HC = perception::OpticalAxesAlongX();
  const double pitch = 15.0 * M_PI / 180.0;
  R_HC = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() * R_HC;
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() = R_WH * R_HC;
  T_WC.translation() = state.p_WB + R_WH * Eigen::Vector3d(-1.6, 0.0, 0.7);
  return T_WC;
}

}  // namespace

void ChaseViewParams::Validate() const {
  if (render_every < 1) {
    throw std::invalid_argument("--chase-every " + std::to_string(render_every) +
                                ": the third-person view needs a render every >= 1 frames");
  }
  if (render_height < 16 || render_height > 2160) {
    throw std::invalid_argument("--chase-height " + std::to_string(render_height) +
                                " px: use 16..2160 (e.g. 240)");
  }
}

ChaseView::ChaseView(const ChaseViewParams& params, int view_height, sim::Scene* scene)
    : params_(params),
      scene_(scene),
      marker_id_(-1),
      view_size_(view_height * 4 / 3, view_height),
      camera_(MakeCamera(ValidatedHeight(params))) {
  sim::Material marker_material;
  marker_material.color = sim::Rgb(0.9f, 0.1f, 0.1f);  // red
  marker_id_ = scene_->AddObject(
      {kMarkerName, sim::Box{Eigen::Vector3d(0.36, 0.36, 0.06)}, marker_material, ParkingPose()});
}

const cv::Mat& ChaseView::Update(int frame_index, const control::QuadState& state,
                                 bool force_render) {
  if (!view_.empty() && frame_index % params_.render_every != 0 && !force_render) return view_;
  const auto start = std::chrono::steady_clock::now();
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = state.q_WB.toRotationMatrix();
  T_WB.translation() = state.p_WB;
  scene_->SetPose(marker_id_, T_WB);
  sim::RenderOptions options;
  options.color = true;
  options.ground_truth = false;
  caster_.Render(*scene_, camera_, ChaseCameraPose(state), options, &output_);
  scene_->SetPose(marker_id_, ParkingPose());
  // Noise-free sensor: gain 1, quantization only.
  const cv::Mat image =
      sim::CameraEffects(sim::CameraEffectsParams{}).ToImage8U(output_.radiance, frame_index);
  if (image.size() == view_size_) {
    view_ = image;
  } else {
    cv::resize(image, view_, view_size_, 0.0, 0.0, cv::INTER_LINEAR);
  }
  render_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++renders_;
  return view_;
}

}  // namespace aperture::apps
