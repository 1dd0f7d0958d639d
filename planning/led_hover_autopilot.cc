#include "planning/led_hover_autopilot.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "perception/led/led_tracker_node.h"

namespace aperture::planning {
void LedHoverAutopilotParams::Validate() const {
  if (camera_id < 0) {
    throw std::invalid_argument("LedHoverAutopilotParams.camera_id must be >= 0, got " +
                                std::to_string(camera_id));
  }
  perception::RequireRigid(T_WC, "LedHoverAutopilotParams.T_WC");
  perception::RequireRigid(T_BT, "LedHoverAutopilotParams.T_BT");
  hold.Validate();
}

namespace {

std::vector<std::unique_ptr<perception::Node>> LedFrontEnd(
    perception::LedConfiguration configuration,
    std::shared_ptr<const perception::CameraModel> camera,
    const perception::LedTrackerParams& params) {
  if (!camera) {
    throw std::invalid_argument(
        "LedHoverAutopilot: the LED camera model is null: pass the model of the camera that "
        "observes the LEDs");
  }
  std::vector<std::unique_ptr<perception::Node>> nodes;
  nodes.push_back(std::make_unique<perception::LedTrackerNode>(
      perception::LedTracker(std::move(configuration), std::move(camera), params)));
  return nodes;
}

}  // namespace

LedHoverAutopilot::LedHoverAutopilot(const control::VehicleParameters& vehicle,
                                     perception::LedConfiguration configuration,
                                     std::shared_ptr<const perception::CameraModel> camera,
                                     const LedHoverAutopilotParams& params)
    : params_((params.Validate(), params)),
      front_ends_(LedFrontEnd(std::move(configuration), std::move(camera), params.tracker)),
      rig_{params.T_WC, params.T_BT, 1.0},
      hold_(vehicle, params.hold, params.setpoint) {}

void LedHoverAutopilot::OnImu(const perception::ImuSample& sample) { hold_.AddImu(sample); }

void LedHoverAutopilot::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id) return;
  const std::vector<perception::PoseObservation>& observations = front_ends_.Process(frame);
  LedHoverFrameRecord record;
  record.t_s = frame.t_s;
  record.track_status =
      front_ends_.Latest<perception::LedTrackResult>(perception::LedTrackerNode::kOutputSlot)
          ->status;
  ++counts_.frames;
  for (const perception::PoseObservation& observation : observations) {
    ++counts_.frames_with_pose;
    record.has_pose = true;
    const perception::PoseMeasurement z = perception::ToPoseMeasurement(observation, rig_);
    record.p_WB = perception::BodyPosition(z);
    for (const perception::PoseFusionOutcome& outcome : hold_.AddPose(z)) {
      if (outcome.started_filter) ++counts_.filter_starts;
      if (!outcome.started_filter && outcome.update.applied()) ++counts_.poses_applied;
      if (outcome.update.status == perception::PoseUpdateStatus::kRejectedOutlier) {
        ++counts_.poses_rejected;
      }
      if (outcome.t_s == z.t_s) record.update = outcome;
    }
  }
  last_frame_ = record;
}

perception::AutopilotCommand LedHoverAutopilot::Step(double t_s) {
  last_step_t_s_ = t_s;
  return hold_.Step(t_s);
}

std::string LedHoverAutopilot::status() const { return hold_.status(last_step_t_s_); }

}  // namespace aperture::planning
