#pragma once
// OpeningTrack: the label tracker's result on one frame (seed 002 Sec. III, Alg. 1), the plain
// struct a contour/safe-point servo consumes. Pixels of the tracked frame, origin at the centre of
// the top-left pixel (camera_model.h).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace aperture::perception {

struct OpeningTrack {
  bool valid = false;  // false before the first detection, or when both sets are lost
  double t_s = 0.0;    // frame time [s]
  int index = -1;      // Frame::index
  // Contour C of the detected opening propagated to this frame (closed polygon) [px].
  std::vector<Eigen::Vector2d> contour_px;
  // Safe point x_s after the Kalman filter, and the switched measurement x_s,F / x_s,B before it.
  Eigen::Vector2d safe_point_px = Eigen::Vector2d::Zero();
  Eigen::Vector2d safe_point_measured_px = Eigen::Vector2d::Zero();
  char safe_point_source = '-';  // 'F' (foreground set) or 'B' (background set)
  // FOE [px] and divergence alpha (per frame; Alg. 1 steps 4-5) of the set x_s comes from;
  // FOE is NaN when |alpha| is too small for it to be defined (pure lateral motion).
  Eigen::Vector2d foe_px = Eigen::Vector2d::Zero();
  double divergence = 0.0;
  int foreground_corners = 0;  // |C_F| and |C_B| tracked into this frame
  int background_corners = 0;
  bool foreground_reset = false;  // corners re-detected this frame (|C| <= k)
  bool background_reset = false;
  double propagation_ms = 0.0;  // Alg. 1 steps 2-6 for both sets (no KLT)
  double klt_ms = 0.0;          // corner tracking (step 1) and resets
};

}  // namespace aperture::perception
