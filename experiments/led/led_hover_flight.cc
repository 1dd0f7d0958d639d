#include "experiments/led/led_hover_flight.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "output/svg_plot.h"
#include "perception/led/led_configuration.h"
#include "sim/sitl/record_window.h"

namespace aperture::experiments {
namespace {

// Ground-truth position at t_s, linear between the recorded states (clamped to their span).
Eigen::Vector3d TruePositionAt(const std::vector<control::QuadState>& trajectory, double t_s) {
  const auto later =
      std::lower_bound(trajectory.begin(), trajectory.end(), t_s,
                       [](const control::QuadState& s, double t) { return s.t_s < t; });
  if (later == trajectory.begin()) return trajectory.front().p_WB;
  if (later == trajectory.end()) return trajectory.back().p_WB;
  const control::QuadState& a = *(later - 1);
  const control::QuadState& b = *later;
  const double w = (t_s - a.t_s) / (b.t_s - a.t_s);
  return (1.0 - w) * a.p_WB + w * b.p_WB;
}

double Heading(const Eigen::Matrix3d& R_WB) { return std::atan2(R_WB(1, 0), R_WB(0, 0)); }

// At most ~max_points samples of a series for a plot (every k-th).
std::size_t PlotStride(std::size_t size, std::size_t max_points = 2000) {
  return std::max<std::size_t>(1, (size + max_points - 1) / max_points);
}

}  // namespace

HoverMetrics ComputeHoverMetrics(const std::vector<control::QuadState>& trajectory,
                                 const Eigen::Vector3d& setpoint_W,
                                 const std::vector<double>& push_times_s, double recovery_radius_m,
                                 double recovery_hold_s) {
  if (trajectory.empty()) throw std::invalid_argument("ComputeHoverMetrics: empty trajectory");
  if (!(recovery_radius_m > 0.0) || !(recovery_hold_s > 0.0)) {
    throw std::invalid_argument(
        "ComputeHoverMetrics: recovery_radius_m and recovery_hold_s must be positive");
  }
  std::vector<double> error(trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    error[i] = (trajectory[i].p_WB - setpoint_W).norm();
  }
  HoverMetrics metrics;
  std::vector<bool> in_window(trajectory.size(), false);
  std::vector<double> pushes = push_times_s;
  std::sort(pushes.begin(), pushes.end());
  const double t_end = trajectory.back().t_s;
  for (const double t_push : pushes) {
    PushRecovery recovery;
    recovery.t_push_s = t_push;
    double inside_since = -1.0;  // < 0: outside the radius
    std::size_t i =
        std::lower_bound(trajectory.begin(), trajectory.end(), t_push,
                         [](const control::QuadState& s, double t) { return s.t_s < t; }) -
        trajectory.begin();
    std::size_t window_end = trajectory.size();  // one past the window
    for (; i < trajectory.size(); ++i) {
      const double t = trajectory[i].t_s;
      if (error[i] <= recovery_radius_m) {
        if (inside_since < 0.0) inside_since = t;
        if (t - inside_since >= recovery_hold_s) break;
      } else {
        inside_since = -1.0;
      }
    }
    if (i < trajectory.size() || (inside_since >= 0.0 && t_end - inside_since >= recovery_hold_s)) {
      recovery.recovery_time_s = inside_since - t_push;
      // The window ends with the first sample back inside (included).
      window_end =
          static_cast<std::size_t>(
              std::lower_bound(trajectory.begin(), trajectory.end(), inside_since,
                               [](const control::QuadState& s, double t) { return s.t_s < t; }) -
              trajectory.begin()) +
          1;
    }
    for (std::size_t k = 0; k < window_end; ++k) {
      if (trajectory[k].t_s < t_push) continue;
      in_window[k] = true;
      recovery.max_error_m = std::max(recovery.max_error_m, error[k]);
    }
    metrics.pushes.push_back(recovery);
  }
  double sum_sq = 0.0, sum_sq_outside = 0.0;
  std::size_t outside = 0;
  for (std::size_t i = 0; i < error.size(); ++i) {
    sum_sq += error[i] * error[i];
    metrics.max_error_m = std::max(metrics.max_error_m, error[i]);
    if (in_window[i]) continue;
    ++outside;
    sum_sq_outside += error[i] * error[i];
    metrics.max_error_outside_pushes_m = std::max(metrics.max_error_outside_pushes_m, error[i]);
  }
  metrics.rms_error_m = std::sqrt(sum_sq / error.size());
  metrics.rms_error_outside_pushes_m = outside > 0 ? std::sqrt(sum_sq_outside / outside) : 0.0;
  return metrics;
}

// LedHoverAutopilot behind a recorder: every LED frame and, after each control step, the estimate
// (the last record_window_s of them when that is > 0, like the SITL records).
class LedHoverFlight::Recorder : public perception::Autopilot {
 public:
  Recorder(const control::VehicleParameters& vehicle, perception::LedConfiguration configuration,
           std::shared_ptr<const perception::CameraModel> camera,
           const planning::LedHoverAutopilotParams& params, double record_window_s)
      : inner_(vehicle, std::move(configuration), std::move(camera), params),
        record_window_s_(record_window_s) {}

  std::string name() const override { return inner_.name(); }
  void OnImu(const perception::ImuSample& sample) override { inner_.OnImu(sample); }
  void OnFrame(const perception::Frame& frame) override {
    const int before = inner_.counts().frames;
    inner_.OnFrame(frame);
    if (inner_.counts().frames == before) return;
    frames_.push_back(inner_.last_frame());
    sim::KeepLastWindow(&frames_, frame.t_s, record_window_s_);
  }
  perception::AutopilotCommand Step(double t_s) override {
    const perception::AutopilotCommand command = inner_.Step(t_s);
    if (const auto estimate = inner_.hold().estimate()) {
      estimates_.push_back({estimate->state.t_s, estimate->state.p_WB, Eigen::Vector3d::Zero()});
      sim::KeepLastWindow(&estimates_, t_s, record_window_s_);
    }
    return command;
  }
  std::string status() const override { return inner_.status(); }

  const planning::LedHoverAutopilot& inner() const { return inner_; }
  const std::vector<planning::LedHoverFrameRecord>& frames() const { return frames_; }
  const std::vector<LedHoverEstimateRecord>& estimates() const { return estimates_; }

 private:
  planning::LedHoverAutopilot inner_;
  const double record_window_s_;
  std::vector<planning::LedHoverFrameRecord> frames_;
  std::vector<LedHoverEstimateRecord> estimates_;
};

LedHoverFlight::LedHoverFlight(const sim::Scenario& scenario, const sim::SitlRunnerParams& params,
                               const LedHoverFlightParams& flight)
    : params_(flight) {
  if (scenario.params().scenario != "led") {
    throw std::invalid_argument("LedHoverFlight needs a scenario of kind 'led', got '" +
                                scenario.params().scenario + "'");
  }
  if (!(flight.recovery_radius_m > 0.0) || !(flight.recovery_hold_s > 0.0)) {
    throw std::invalid_argument(
        "LedHoverFlightParams.recovery_radius_m and recovery_hold_s must be positive");
  }
  int camera_id = -1;
  for (int i = static_cast<int>(params.cameras.size()) - 1; i >= 0; --i) {
    if (params.cameras[i].T_WC_fixed) camera_id = i;
  }
  if (camera_id < 0) {
    throw std::invalid_argument(
        "LedHoverFlight: the scenario has no world-fixed camera (cameras.<name>.mount_on_body: "
        "false) to observe the LEDs");
  }
  planning::LedHoverAutopilotParams autopilot;
  autopilot.camera_id = camera_id;
  autopilot.T_WC = *params.cameras[camera_id].T_WC_fixed;
  autopilot.T_BT = Eigen::Isometry3d::Identity();  // the scenario places the LEDs in B
  autopilot.setpoint.p_W = params.initial_state.p_WB;
  autopilot.setpoint.heading_rad = Heading(params.initial_state.q_WB.toRotationMatrix());
  autopilot.tracker = flight.tracker;
  autopilot.hold = flight.hold;
  recorder_ = std::make_unique<Recorder>(
      params.dynamics.vehicle,
      perception::LedConfiguration(scenario.params().led.leds_B,
                                   scenario.params().led.config.empty()
                                       ? "led scenario (led.leds)"
                                       : scenario.params().led.config),
      params.cameras[camera_id].model, autopilot, params.record_window_s);
}

LedHoverFlight::~LedHoverFlight() = default;

perception::Autopilot& LedHoverFlight::autopilot() { return *recorder_; }

void LedHoverFlight::DrawOverlay(cv::Mat& bgr) const {
  recorder_->inner().front_ends().DrawOverlays(bgr);
}

LedHoverFlightResult LedHoverFlight::Finish(const sim::SitlResult& sitl,
                                            const std::vector<sim::Push>& pushes) const {
  LedHoverFlightResult result;
  const planning::LedHoverAutopilot& autopilot = recorder_->inner();
  result.setpoint = autopilot.hold().setpoint();
  std::vector<double> push_times;
  for (const sim::Push& push : pushes) {
    // Pushes within the recorded trajectory (all of them unless SITL keeps a record window).
    if (push.t_s <= sitl.sim_time_s && push.t_s >= sitl.trajectory.front().t_s) {
      push_times.push_back(push.t_s);
    }
  }
  result.hover = ComputeHoverMetrics(sitl.trajectory, result.setpoint.p_W, push_times,
                                     params_.recovery_radius_m, params_.recovery_hold_s);
  result.counts = autopilot.counts();
  result.sim_time_s = sitl.sim_time_s;
  result.pose_rate_hz =
      sitl.sim_time_s > 0.0 ? result.counts.frames_with_pose / sitl.sim_time_s : 0.0;
  result.frames = recorder_->frames();
  double led_sum_sq = 0.0;
  for (const planning::LedHoverFrameRecord& frame : result.frames) {
    if (!frame.has_pose) {
      result.led_pose_error_m.push_back(std::nan(""));
      continue;
    }
    const double error = (frame.p_WB - TruePositionAt(sitl.trajectory, frame.t_s)).norm();
    result.led_pose_error_m.push_back(error);
    led_sum_sq += error * error;
  }
  if (result.counts.frames_with_pose > 0) {
    result.led_pose_rms_error_m = std::sqrt(led_sum_sq / result.counts.frames_with_pose);
  }
  result.estimates = recorder_->estimates();
  double sum_sq = 0.0;
  for (LedHoverEstimateRecord& e : result.estimates) {
    e.p_true_W = TruePositionAt(sitl.trajectory, e.t_s);
    const double error = (e.p_est_W - e.p_true_W).norm();
    sum_sq += error * error;
    result.estimate_max_error_m = std::max(result.estimate_max_error_m, error);
  }
  if (!result.estimates.empty()) {
    result.estimate_rms_error_m = std::sqrt(sum_sq / result.estimates.size());
  }
  return result;
}

nlohmann::json LedHoverSummary(const LedHoverFlightResult& result) {
  const Eigen::Vector3d& p = result.setpoint.p_W;
  nlohmann::json pushes = nlohmann::json::array();
  for (const PushRecovery& push : result.hover.pushes) {
    pushes.push_back(
        {{"t_s", push.t_push_s},
         {"max_error_m", push.max_error_m},
         {"recovered", push.recovery_time_s.has_value()},
         {"recovery_time_s",
          push.recovery_time_s ? nlohmann::json(*push.recovery_time_s) : nlohmann::json(nullptr)}});
  }
  const planning::LedHoverCounts& c = result.counts;
  return {{"setpoint_p_W_m", {p.x(), p.y(), p.z()}},
          {"setpoint_heading_rad", result.setpoint.heading_rad},
          {"hover_error_m",
           {{"rms", result.hover.rms_error_m},
            {"max", result.hover.max_error_m},
            {"rms_outside_push_recovery", result.hover.rms_error_outside_pushes_m},
            {"max_outside_push_recovery", result.hover.max_error_outside_pushes_m}}},
          {"pushes", pushes},
          {"led_pose",
           {{"frames", c.frames},
            {"frames_with_pose", c.frames_with_pose},
            {"frames_without_pose", c.frames - c.frames_with_pose},
            {"rate_hz", result.pose_rate_hz},
            {"applied", c.poses_applied},
            {"rejected_outliers", c.poses_rejected},
            {"filter_starts", c.filter_starts}}},
          {"led_pose_rms_error_m", result.led_pose_rms_error_m},
          {"estimate_error_m",
           {{"rms", result.estimate_rms_error_m},
            {"max", result.estimate_max_error_m},
            {"samples", result.estimates.size()}}}};
}

void AddLedHoverReport(const LedHoverFlightResult& result, output::HtmlReport* report) {
  report->AddSection("LED-stabilized hover");
  const std::size_t stride = PlotStride(result.estimates.size());
  std::vector<double> t, est[3], truth[3], setpoint[3], error;
  for (std::size_t i = 0; i < result.estimates.size(); i += stride) {
    const LedHoverEstimateRecord& e = result.estimates[i];
    t.push_back(e.t_s);
    for (int a = 0; a < 3; ++a) {
      est[a].push_back(e.p_est_W(a));
      truth[a].push_back(e.p_true_W(a));
      setpoint[a].push_back(result.setpoint.p_W(a));
    }
    error.push_back((e.p_est_W - e.p_true_W).norm());
  }
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    report->AddSvg(output::SvgPlot({std::string("Position ") + axes[a] + " vs set-point", "t [s]",
                                    std::string("p_") + axes[a] + " [m]"})
                       .AddLine("set-point", t, setpoint[a])
                       .AddLine("ground truth", t, truth[a])
                       .AddLine("estimate (LED + IMU)", t, est[a])
                       .Render());
  }
  report->AddSvg(output::SvgPlot({"Estimate error |p_est - p_true|", "t [s]", "error [m]"})
                     .AddLine("estimate error", t, error)
                     .Render());
  std::vector<double> t_frame, frame_error;
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    if (!result.frames[i].has_pose) continue;
    t_frame.push_back(result.frames[i].t_s);
    frame_error.push_back(result.led_pose_error_m[i]);
  }
  report->AddSvg(
      output::SvgPlot({"LED pose error |p_WB,LED - p_WB| per frame", "t [s]", "error [m]"})
          .AddScatter("LED pose (T_WC T_CT T_BT^-1)", t_frame, frame_error)
          .Render());
  std::vector<double> t_lost, lost;
  for (const planning::LedHoverFrameRecord& frame : result.frames) {
    if (frame.has_pose) continue;
    t_lost.push_back(frame.t_s);
    lost.push_back(1.0);
  }
  report->AddSvg(output::SvgPlot({"LED frames without a pose", "t [s]", "1 = no pose"})
                     .AddScatter("no pose", t_lost, lost)
                     .Render());
}

}  // namespace aperture::experiments
