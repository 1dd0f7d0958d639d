#pragma once
// SIMULATION ONLY: the initialization of a monocular visual-inertial pipeline (SVO + MSF in
// Faessler thesis B.3.2, stage 3) emulated from ground truth, with the failure mode B.4.2 reports:
// "failures occurred when the vision pipeline could not initialize properly, e.g., when flying
// close to the ground with high velocities".
//
// The downward camera tracks ground features while the body is within max_tilt_rad of level,
// at least min_height_m above the ground (closer, the view is out of focus and holds too few
// features), and the ground's image flow, |v_xy| / h + |omega_xy| [rad/s], stays below
// max_flow_radps (faster, features blur and are lost). While it tracks, the horizontal translation
// accumulates; initialization needs min_baseline_ratio * h of it (triangulation parallax). Losing
// the features restarts the count. At initialization the scale comes from the height estimate, as
// in the thesis ("an initial scale corresponding to the current height estimate"): s = h_est /
// h_true times (1 + N(0, scale_noise)). From then on the estimate is the ground truth of
// latency_s ago in the vision frame V, scaled by s, with white noise:
//   p_V = s R_VW p_W + offset_W + n_p,  v_V = s R_VW v_W + n_v,  q_VB = R_VW q_WB.
// R_VW is the heading offset the caller sets at initialization (the IMU attitude estimator's yaw
// is arbitrary).
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>

#include "control/quad_state.h"

namespace aperture::sim {

struct VisualInitializationParams {
  double max_tilt_rad = 0.3490658503988659;  // 20 deg: the camera sees the ground (B.3.2)
  double min_height_m = 0.3;
  double max_flow_radps = 3.0;
  double min_baseline_ratio = 0.1;
  double latency_s = 0.03;                             // image to estimate
  double position_noise_m = 0.005;                     // white, per estimate
  double velocity_noise_mps = 0.02;                    // white, per estimate
  double scale_noise = 0.03;                           // relative, drawn once at initialization
  Eigen::Vector3d offset_W = Eigen::Vector3d::Zero();  // origin of V [m]
  // Throws std::invalid_argument naming the field (negative, non-finite).
  void Validate() const;
};

class VisualInitialization {
 public:
  // Throws std::invalid_argument for invalid params.
  VisualInitialization(const VisualInitializationParams& params, std::uint64_t seed);

  // One step with the true state (increasing t_s); `attempt`: the recovery wants the vision
  // pipeline (its height stage); `estimated_height_m`: the height filter's estimate, for the scale.
  // Returns true on the step that initializes.
  bool Update(const control::QuadState& truth, bool attempt, double estimated_height_m);
  // Heading offset of V (set once, at initialization).
  void SetVisionRotation(const Eigen::Matrix3d& R_VW) { R_VW_ = R_VW; }

  bool initialized() const { return initialized_; }
  double initialized_at_s() const { return initialized_at_s_; }
  double scale() const { return scale_; }
  // Translation tracked towards initialization so far [m].
  double baseline_m() const { return baseline_m_; }
  // The estimate for the latest step (nullopt before initialization or before latency_s of
  // states has passed since it).
  std::optional<control::QuadState> Estimate();

 private:
  VisualInitializationParams params_;
  std::mt19937_64 rng_;
  std::deque<control::QuadState> states_;  // the last latency_s of ground truth
  std::optional<Eigen::Vector2d> last_tracked_xy_W_;
  double baseline_m_ = 0.0;
  bool initialized_ = false;
  double initialized_at_s_ = -1.0;
  double scale_ = 1.0;
  Eigen::Matrix3d R_VW_ = Eigen::Matrix3d::Identity();
};

}  // namespace aperture::sim
