#pragma once
// Third-person view of `aperture sim`: the scene from 1.6 m behind and 0.7 m above the vehicle
// in its heading frame (no roll/pitch, so the horizon stays level), looking forward 15 deg down,
// 70 deg horizontal field of view, colour, 4:3, with a red box marking the vehicle.
//
// For the video it is rendered at render_height (a quarter of the pixels of the 480-row onboard
// view by default) on every render_every-th video frame and shown scaled to the onboard view's
// height; frames in between repeat the last view (a 15 frames/s video: a 7.5 Hz chase view). Its
// cost is booked in render_s(), apart from the onboard cameras. Usage (before the SitlRunner is
// built, so the collision check can ignore the marker):
//   ChaseView chase(ChaseViewParams{}, 480, &scenario.scene());
//   params.collision.ignored_objects.push_back(ChaseView::kMarkerName);
//   ... per video frame: cv::hconcat(onboard, chase.Update(index, state, false), composite);
#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "control/quad_state.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/scene.h"

namespace aperture::apps {

struct ChaseViewParams {
  int render_every = 2;     // video frames per chase render (>= 1)
  int render_height = 240;  // rendered rows (width 4/3 of it) before scaling to the video [px]
  // Throws std::invalid_argument naming the option (--chase-every, --chase-height) when out of
  // range: render_every < 1, render_height outside [16, 2160].
  void Validate() const;
};

class ChaseView {
 public:
  // Adds the vehicle marker box to *scene (parked far below the ground between renders; name
  // kMarkerName, for the collision check's ignore list). `view_height`: rows of the view in the
  // video. The scene must outlive the view.
  ChaseView(const ChaseViewParams& params, int view_height, sim::Scene* scene);

  static constexpr const char* kMarkerName = "sitl_vehicle_marker";

  // The view for video frame `frame_index` (0, 1, ...) with the vehicle at `state`: rendered
  // afresh when frame_index % render_every == 0 or `force_render`, else the previous one.
  // BGR 8-bit, view_height x 4/3 view_height.
  const cv::Mat& Update(int frame_index, const control::QuadState& state, bool force_render);

  double render_s() const { return render_s_; }  // wall time of the renders [s]
  int renders() const { return renders_; }

 private:
  ChaseViewParams params_;
  sim::Scene* scene_;
  int marker_id_;
  cv::Size view_size_;
  perception::PinholeCamera camera_;
  sim::RayCaster caster_;
  sim::RenderOutput output_;
  cv::Mat view_;
  double render_s_ = 0.0;
  int renders_ = 0;
};

}  // namespace aperture::apps
