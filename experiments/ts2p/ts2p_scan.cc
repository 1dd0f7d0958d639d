#include "experiments/ts2p/ts2p_scan.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "control/constants.h"
#include "sim/scenario/scenario.h"

namespace aperture::experiments {
namespace {

using control::kDegToRad;
// Height of the body (and camera) during the scan: the built-in gapflyt start height.
constexpr double kBodyHeightM = 1.5;

// The gapflyt scene of a config and captures from poses along its scan line / approach.
class GapflytRig {
 public:
  explicit GapflytRig(const Ts2pScanConfig& config) : config_(config), scenario_(Build(config)) {
    wall_id_ = scenario_.scene().FindId("gap");
    const double angle = config.scan_angle_deg * kDegToRad;
    // Scan direction in the wall plane: "right" = -y_W, "up" = +z_W.
    direction_W_ = Eigen::Vector3d(0.0, -std::cos(angle), std::sin(angle));
  }

  const sim::ScenarioCamera& camera() const { return scenario_.render_camera(); }

  // Camera pose `offset` scan steps along the line (rotated by offset * rotation_per_step) and
  // `forward_m` towards the wall.
  Eigen::Isometry3d T_WC(double offset, double forward_m) const {
    Eigen::Isometry3d T_WB = scenario_.T_WB_start();
    T_WB.translation() +=
        offset * config_.scan_step_m * direction_W_ + forward_m * Eigen::Vector3d::UnitX();
    Eigen::Isometry3d T_WC = camera().T_WC(T_WB);
    // Rotation about the camera's own axes (z roll, x pitch, y yaw), proportional to the offset.
    const Eigen::Vector3d rate = config_.rotation_per_step_deg * kDegToRad;
    const Eigen::Matrix3d R_CrCk = (Eigen::AngleAxisd(offset * rate.x(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(offset * rate.y(), Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(offset * rate.z(), Eigen::Vector3d::UnitY()))
                                       .toRotationMatrix();
    T_WC.linear() = T_WC.linear() * R_CrCk;
    return T_WC;
  }

  // Gray image at T_WC; *truth (optional) = G.
  cv::Mat Capture(const Eigen::Isometry3d& T_WC, double forward_m, int index,
                  sim::RayCaster& caster, cv::Mat* truth) const {
    sim::CapturedFrame frame = camera().effects.Capture(
        caster, scenario_.scene(), *camera().model, [&](double) { return T_WC; }, index / 30.0,
        index, camera().render);
    // G: seen through the hole, i.e. not the wall and behind the wall's plane (the ground in
    // front of the wall, at the image bottom, is not part of the opening). The scan camera faces
    // the wall squarely, so the wall's plane is at z_C = Z_F (minus the approach distance).
    if (truth) {
      const double wall_z_m = config_.foreground_depth_m - forward_m;
      *truth = (frame.object_id != wall_id_) & (frame.depth_C > wall_z_m);
    }
    return frame.frame.image;
  }

 private:
  static sim::Scenario Build(const Ts2pScanConfig& config) {
    if (config.stack < 1) {
      throw std::invalid_argument("Ts2pScanConfig.stack must be >= 1, got " +
                                  std::to_string(config.stack));
    }
    sim::ScenarioParams params = sim::LoadScenarioParams(sim::ScenarioConfig("gapflyt"));
    params.seed = config.seed;
    sim::CameraParams& camera_params = params.cameras.front().second;
    camera_params.width = config.width;
    camera_params.height = config.height;
    camera_params.fov_deg = config.fov_deg;
    const double camera_x_m = camera_params.pose.p_m.x();
    params.gapflyt.shape = config.shape;
    params.gapflyt.size_m = config.opening_size_m;
    // Wall "right" seen from the start is -y_W.
    params.gapflyt.center_m =
        Eigen::Vector2d(-config.opening_offset_m.x(), kBodyHeightM + config.opening_offset_m.y());
    params.gapflyt.foreground_x_m = camera_x_m + config.foreground_depth_m;
    params.gapflyt.background_x_m = camera_x_m + config.background_depth_m;
    params.vehicle_start.p_m = Eigen::Vector3d(0.0, 0.0, kBodyHeightM);
    params.vehicle_start.rpy_deg.setZero();
    return sim::BuildScenario(params);
  }

  Ts2pScanConfig config_;
  sim::Scenario scenario_;
  int wall_id_ = -1;
  Eigen::Vector3d direction_W_;
};

}  // namespace

const std::vector<std::string> kTs2pShapes{"ellipse", "polygon", "triangle", "notched", "star"};

Ts2pScan RenderTs2pScan(const Ts2pScanConfig& config, sim::RayCaster& caster) {
  const GapflytRig rig(config);
  Ts2pScan scan;
  scan.camera = rig.camera().model;
  const int half = config.stack / 2;
  scan.reference = rig.Capture(rig.T_WC(0.0, 0.0), 0.0, half, caster, &scan.truth);
  const Eigen::Matrix3d R_WCr = rig.T_WC(0.0, 0.0).linear();
  for (int k = 0; k <= config.stack; ++k) {
    if (k == half) continue;
    // N = 1: the one frame after the reference.
    const double offset = config.stack == 1 ? 1.0 : static_cast<double>(k - half);
    const Eigen::Isometry3d T_WC = rig.T_WC(offset, 0.0);
    scan.frames.push_back(rig.Capture(T_WC, 0.0, k, caster, nullptr));
    scan.R_CkCr.push_back(T_WC.linear().transpose() * R_WCr);
  }
  return scan;
}

Ts2pApproach RenderTs2pApproach(const Ts2pScanConfig& config, int frames, double speed_mps,
                                sim::RayCaster& caster) {
  if (frames < 1 || !(speed_mps >= 0.0)) {
    throw std::invalid_argument("RenderTs2pApproach: frames must be >= 1 and speed_mps >= 0");
  }
  const GapflytRig rig(config);
  Ts2pApproach approach;
  for (int k = 1; k <= frames; ++k) {
    cv::Mat truth;
    const double forward_m = k * speed_mps / approach.frame_rate_hz;
    approach.frames.push_back(
        rig.Capture(rig.T_WC(0.0, forward_m), forward_m, 100 + k, caster, &truth));
    approach.truth.push_back(truth);
  }
  return approach;
}

Ts2pScanConfig DrawTs2pTrial(const Ts2pTrialRanges& ranges, std::uint64_t seed, int trial) {
  // A generator of (seed, trial) alone: trials are independent of order and thread.
  std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                         static_cast<std::uint32_t>(trial), 0x74733270u /* "ts2p" */};
  std::mt19937_64 rng(sequence);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](const Eigen::Vector2d& range) {
    return range.x() + (range.y() - range.x()) * unit(rng);
  };
  Ts2pScanConfig config;
  config.shape = kTs2pShapes[static_cast<std::size_t>(trial) % kTs2pShapes.size()];
  config.seed = rng();
  config.foreground_depth_m = uniform(ranges.foreground_depth_m);
  config.background_depth_m = uniform(ranges.background_depth_m);
  config.opening_size_m = Eigen::Vector2d(uniform(ranges.width_m), uniform(ranges.height_m));
  config.opening_offset_m = Eigen::Vector2d(uniform({-ranges.max_offset_m, ranges.max_offset_m}),
                                            uniform({-ranges.max_offset_m, ranges.max_offset_m}));
  config.scan_angle_deg = uniform(ranges.scan_angle_deg);
  return config;
}

}  // namespace aperture::experiments
