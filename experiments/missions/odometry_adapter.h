#pragma once
// What the SITL flies for a mission that flies on the vehicle's odometry source (a VIO on
// hardware): the mission, with a simulated one (sim::OdometrySensor: noisy ground-truth body
// poses, no drift) fed from ground truth and handed to the mission's OnOdometry; every other call
// is forwarded, so the mission itself never sees ground truth. Used by the forest, the tag
// mapping and follow flights, and the gap mission's recovery (its downward camera's SVO).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "experiments/missions/mission_registry.h"
#include "perception/autopilot.h"
#include "sim/sensors/odometry_sensor.h"
#include "sim/sim_params_io.h"

namespace aperture::experiments {

class OdometryAdapter final : public perception::Autopilot {
 public:
  using OdometrySink = std::function<void(const perception::PoseMeasurement& pose_WB)>;
  // `mission` outlives the adapter; `on_odometry` receives the sensor's body poses.
  OdometryAdapter(perception::Autopilot* mission, OdometrySink on_odometry,
                  const sim::OdometrySensorParams& odometry)
      : mission_(mission), on_odometry_(std::move(on_odometry)), odometry_(odometry) {}
  std::string name() const override { return mission_->name(); }
  void OnImu(const perception::ImuSample& sample) override { mission_->OnImu(sample); }
  void OnFrame(const perception::Frame& frame) override { mission_->OnFrame(frame); }
  void OnRange(const perception::RangeReading& reading) override { mission_->OnRange(reading); }
  bool WantsFrame(int camera_id, double t_s) const override {
    return mission_->WantsFrame(camera_id, t_s);
  }
  bool UsesGroundTruth() const override { return true; }  // the odometry sensor's input only
  void OnGroundTruth(const control::QuadState& state) override {
    if (auto pose = odometry_.Update(state)) on_odometry_(*pose);
  }
  perception::AutopilotCommand Step(double t_s) override { return mission_->Step(t_s); }
  std::string status() const override { return mission_->status(); }

 private:
  perception::Autopilot* mission_;
  OdometrySink on_odometry_;
  sim::OdometrySensor odometry_;
};

// Salt of the gap mission's recovery odometry (gap flight and gap bench trials draw the same).
constexpr std::uint64_t kGapOdometrySalt = 37;

// The odometry source's parameters of a mission flight: seeded from the scenario's seed (times
// 7919 plus `salt`, so two missions do not draw the same noise), then the `odometry` section of
// `mission` (read before the mission's own keys, which reject the rest).
inline sim::OdometrySensorParams OdometryParamsFor(const sim::Scenario& scenario,
                                                   std::uint64_t salt) {
  sim::OdometrySensorParams odometry;
  odometry.seed = scenario.params().seed * 7919 + salt;
  return odometry;
}
inline sim::OdometrySensorParams LoadOdometryParams(const MissionContext& context,
                                                    std::uint64_t salt) {
  sim::OdometrySensorParams odometry = OdometryParamsFor(context.scenario, salt);
  context.params.ReadSection("odometry", &odometry);
  return odometry;
}

// The adapter for a mission with OnOdometry(const perception::PoseMeasurement&).
template <typename Mission>
std::unique_ptr<OdometryAdapter> MakeOdometryAdapter(Mission* mission,
                                                     const sim::OdometrySensorParams& odometry) {
  return std::make_unique<OdometryAdapter>(
      mission,
      [mission](const perception::PoseMeasurement& pose_WB) { mission->OnOdometry(pose_WB); },
      odometry);
}

}  // namespace aperture::experiments
