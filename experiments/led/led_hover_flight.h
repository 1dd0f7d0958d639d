#pragma once
// The LED-stabilized hover of `aperture sim led` (issue 6, Faessler thesis C.4.3) on a `led`
// scenario: the scenario's world-fixed camera observes the LEDs on the vehicle and
// planning::LedHoverAutopilot holds the start pose from the LED pose and the IMU only. Ground
// truth never reaches the autopilot; it only scores the flight afterwards.
//
//   Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig("led", {}, sets)));
//   SitlRunnerParams params;  params.SetSeed(seed);  ConfigureSitlFromScenario(scenario, &params);
//   LedHoverFlight flight(scenario, params);            // LED camera, layout, set-point
//   SitlResult sitl = SitlRunner(params, &scenario.scene())
//                         .Run(flight.autopilot(), MakeScenarioHooks(&scenario));
//   LedHoverFlightResult result = flight.Finish(sitl, params.disturbances.pushes);
//
// Scores (SI units): hover error |p_WB - p_set| over the ground-truth trajectory (RMS, max, and
// both outside the push-recovery windows), per push the peak error and the recovery time (from
// the push until the error is back within recovery_radius_m for recovery_hold_s), the estimate
// error |p_WB,est - p_WB| at every control step, the LED pose rate and frames without a pose.
// With SitlRunnerParams::record_window_s set, the per-frame and per-step records (and so the
// scores, not the counts) cover the last window of the flight only, like the SITL records.
#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

#include "control/quad_state.h"
#include "output/html_report.h"
#include "perception/led/led_tracker.h"
#include "planning/led_hover_autopilot.h"
#include "planning/pose_hold.h"
#include "sim/scenario/scenario.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

struct LedHoverFlightParams {
  planning::PoseHoldParams hold;
  perception::LedTrackerParams tracker;
  double recovery_radius_m = 0.1;  // "back within 10 cm" of the set-point
  double recovery_hold_s = 1.0;    // ... and staying there this long [s]
};

// One control step: the autopilot's estimate (at its latest IMU sample) and the ground truth then.
struct LedHoverEstimateRecord {
  double t_s = 0.0;
  Eigen::Vector3d p_est_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_true_W = Eigen::Vector3d::Zero();
};

struct PushRecovery {
  double t_push_s = 0.0;
  double max_error_m = 0.0;               // peak |p - p_set| from the push until recovered / end
  std::optional<double> recovery_time_s;  // none: not recovered before the run ended
};

struct HoverMetrics {
  double rms_error_m = 0.0;  // whole run
  double max_error_m = 0.0;
  double rms_error_outside_pushes_m = 0.0;  // samples outside [push, push + recovery time]
  double max_error_outside_pushes_m = 0.0;
  std::vector<PushRecovery> pushes;
};

// Scores a ground-truth trajectory (t_s increasing) against a fixed set-point. A push that is
// never recovered extends its window to the end of the run. Throws std::invalid_argument for an
// empty trajectory or non-positive radius / hold time.
HoverMetrics ComputeHoverMetrics(const std::vector<control::QuadState>& trajectory,
                                 const Eigen::Vector3d& setpoint_W,
                                 const std::vector<double>& push_times_s, double recovery_radius_m,
                                 double recovery_hold_s);

struct LedHoverFlightResult {
  planning::PoseHoldSetpoint setpoint;
  HoverMetrics hover;
  planning::LedHoverCounts counts;
  double sim_time_s = 0.0;
  double pose_rate_hz = 0.0;                          // LED poses per simulated second
  std::vector<planning::LedHoverFrameRecord> frames;  // every LED-camera frame
  std::vector<double> led_pose_error_m;  // per frame: |p_WB,LED - p_WB| (NaN without a pose)
  double led_pose_rms_error_m = 0.0;     // over the frames with a pose
  std::vector<LedHoverEstimateRecord> estimates;  // every control step after the first pose
  double estimate_rms_error_m = 0.0;              // over `estimates`
  double estimate_max_error_m = 0.0;
};

class LedHoverFlight {
 public:
  // Uses the scenario's first world-fixed camera (T_WC = its pose), its LED layout (led.leds_B,
  // target frame = body: T_BT = I) and its start pose as the set-point, the vehicle model of
  // `params.dynamics`. Throws std::invalid_argument if the scenario is not of kind `led`, has no
  // world-fixed camera, or for invalid flight params.
  LedHoverFlight(const sim::Scenario& scenario, const sim::SitlRunnerParams& params,
                 const LedHoverFlightParams& flight = {});
  ~LedHoverFlight();

  // The autopilot to fly (LedHoverAutopilot behind a recorder for the scores).
  perception::Autopilot& autopilot();
  // The LED front end's overlay of the latest LED-camera frame onto `bgr` (that camera's size).
  void DrawOverlay(cv::Mat& bgr) const;
  // Scores the run (its ground-truth trajectory and the recorded estimates).
  LedHoverFlightResult Finish(const sim::SitlResult& sitl,
                              const std::vector<sim::Push>& pushes) const;

 private:
  class Recorder;
  LedHoverFlightParams params_;
  std::unique_ptr<Recorder> recorder_;
};

// summary.json section (the figures of the result) and the report's plots: position vs
// set-point, estimate vs ground truth, estimate error.
nlohmann::json LedHoverSummary(const LedHoverFlightResult& result);
void AddLedHoverReport(const LedHoverFlightResult& result, output::HtmlReport* report);

}  // namespace aperture::experiments
