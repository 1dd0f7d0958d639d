#include "experiments/control/low_level_sections.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "control/constants.h"
#include "control/low_level_controller.h"
#include "control/mixer.h"
#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/reference_trajectories.h"
#include "experiments/bench/sample_statistics.h"
#include "output/svg_plot.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/sitl/tracking_flight.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::experiments {
namespace {

using control::kPi;
constexpr double kHoverHeight_m = 1.5;
constexpr double kControlRate_hz = 100.0;  // high-level loop on ground truth (G.6 mocap setting)
constexpr double kRecordRate_hz = 100.0;   // ground truth kept for the figures

double Yaw(const Eigen::Quaterniond& q_WB) {
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}
// Heading error as the attitude controller sees it (thesis B.16-B.20): the yaw part q_e,y of the
// attitude error, i.e. the angle about z_des from the x axis of the attitude tilted onto z_des
// (shortest rotation, B.10-B.12) to that of R_des, for the desired attitude the position
// controller computes at this state. A difference of atan2 yaw angles would add second-order
// terms of the tilt and of any steady tilt error, which are not heading errors.
double HeadingError(const control::PositionController& controller, const control::QuadState& state,
                    const control::TrajectoryPoint& reference) {
  const Eigen::Matrix3d R_des = controller.Compute(state, reference).attitude.R_des_WB;
  const Eigen::Matrix3d R = state.q_WB.toRotationMatrix();
  const Eigen::Matrix3d R_tilted =
      Eigen::Quaterniond::FromTwoVectors(R.col(2), R_des.col(2)).toRotationMatrix() * R;
  return std::atan2(R_tilted.col(0).dot(R_des.col(1)), R_tilted.col(0).dot(R_des.col(0)));
}
double WrapAngle(double angle_rad) { return std::remainder(angle_rad, 2.0 * kPi); }
double Tilt(const Eigen::Quaterniond& q_WB) {
  return std::acos(std::clamp((q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
}
double Rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}
double MeanOrZero(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}
double MaxAbs(const std::vector<double>& values) {
  double m = 0.0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

// SITL run of the bench vehicle and flight controller starting in hover at p_W: no cameras, no
// range sensor, the bench IMU, every random stream from options.seed. Its dynamics are still the
// nominal model: WithBenchVehicle applies the mismatch once the section has set up the flight.
sim::SitlRunnerParams BenchRunParams(const ControlBenchOptions& options, double duration_s,
                                     const Eigen::Vector3d& p_W) {
  sim::SitlRunnerParams params;
  params.dynamics = options.dynamics;
  params.imu = options.imu;
  params.flight_controller.low_level = options.control.low_level;
  params.duration_s = duration_s;
  params.control_rate_hz = kControlRate_hz;
  params.initial_state.p_WB = p_W;
  params.range_enabled = false;
  params.trajectory_decimation =
      static_cast<int>(std::lround(params.dynamics_rate_hz / kRecordRate_hz));
  params.SetSeed(options.seed);
  return params;
}

// Position control on ground truth with the bench's gains and drag switch.
sim::GroundTruthAutopilotParams BenchAutopilot(const ControlBenchOptions& options) {
  sim::GroundTruthAutopilotParams params;
  params.controller = options.control.position;
  return params;
}

// `params` with the simulated vehicle of the bench (vehicle.mismatch: drawn from options.seed,
// the nominal dynamics becoming the flight controller's model).
sim::SitlRunnerParams WithBenchVehicle(sim::SitlRunnerParams params,
                                       const ControlBenchOptions& options) {
  sim::ApplyVehicleMismatch(options.vehicle, options.seed, &params);
  return params;
}

// A hover at the start point; the autopilot models the nominal vehicle of `params`.
sim::SitlResult FlyHover(const sim::SitlRunnerParams& params, const ControlBenchOptions& options,
                         double heading_rad = 0.0) {
  sim::GroundTruthAutopilotParams autopilot_params = BenchAutopilot(options);
  autopilot_params.waypoints.push_back({params.initial_state.p_WB, heading_rad, 0.0});
  sim::GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  sim::SitlRunner runner(WithBenchVehicle(params, options), nullptr);
  return runner.Run(autopilot);
}

// ---------------------------------------------------------------------------------------------
// body_rate

struct BodyRateController {
  std::string key;    // summary key
  std::string label;  // plot legend
  control::LowLevelControllerParameters params;
};

// The three laws of Table G.1 on the bench's flight controller (its mixer and LQR weights).
std::vector<BodyRateController> BodyRateControllers(const ControlBenchOptions& options) {
  using Law = control::LowLevelControllerParameters::BodyRateLaw;
  const control::LowLevelControllerParameters& base = options.control.low_level;
  BodyRateController p_low{"p_low", "(a) P low gain", base};
  p_low.params.body_rate_law = Law::kProportional;
  p_low.params.proportional = control::ProportionalBodyRateParameters::LowGain();
  BodyRateController p_high{"p_high", "(b) P high gain", base};
  p_high.params.body_rate_law = Law::kProportional;
  p_high.params.proportional = control::ProportionalBodyRateParameters::HighGain();
  // The default LQR weights give rate gains equal to (b) (G.6.2 "equivalent gains to (b)").
  BodyRateController lqr{"lqr", "(c) LQR", base};
  lqr.params.body_rate_law = Law::kLqr;
  return {p_low, p_high, lqr};
}

// Settled after a hit: body rates below 0.35 rad/s (20 deg/s) and tilt below 2 deg, i.e. the hit's
// peak (~200 deg/s, ~10 deg) reduced to about a tenth; measured until it holds for good.
constexpr double kSettledRate_radps = 0.35;
constexpr double kSettledTilt_rad = 2.0 * kPi / 180.0;
constexpr double kHitSpacing_s = 2.5;    // hover time between hits: all three controllers settle
constexpr double kHitImpulse_Ns = 0.02;  // upward, +-25 % (seeded): ~2.5 rad/s per roll/pitch axis

struct HitResponse {
  std::vector<double> settling_times_s;
  // Trace of the first hit: time since the hit, |omega_B| and tilt.
  std::vector<double> t_s, rate_radps, tilt_deg;
};

HitResponse FlyHits(const BodyRateController& controller, const ControlBenchOptions& options) {
  const int hits = options.quick ? 2 : 10;  // Fig. G.5 averages over 10 disturbances
  sim::SitlRunnerParams params = BenchRunParams(options, 1.0 + hits * kHitSpacing_s,
                                                Eigen::Vector3d(0.0, 0.0, kHoverHeight_m));
  params.flight_controller.low_level = controller.params;
  std::mt19937_64 rng(options.seed * 7919 + 17);
  std::uniform_real_distribution<double> scale(0.75, 1.25);
  const control::VehicleParameters& vehicle = params.dynamics.vehicle;
  std::vector<double> hit_times_s;
  for (int k = 0; k < hits; ++k) {
    const double J_Ns = kHitImpulse_Ns * scale(rng);
    sim::Push push;
    push.t_s = 1.0 + k * kHitSpacing_s;
    push.impulse_W_Ns = Eigen::Vector3d(0.0, 0.0, J_Ns);
    // Hit on arm k mod 4 from below: the force acts at the rotor, r_i x F (hover: z_B ~ z_W).
    push.angular_impulse_B_Nms = vehicle.RotorPosition_B(k % 4).cross(push.impulse_W_Ns);
    params.disturbances.pushes.push_back(push);
    hit_times_s.push_back(push.t_s);
  }
  const sim::SitlResult result = FlyHover(params, options);
  HitResponse response;
  for (double t_hit : hit_times_s) {
    double last_unsettled_s = t_hit;
    for (const control::QuadState& state : result.trajectory) {
      if (state.t_s < t_hit || state.t_s >= t_hit + kHitSpacing_s) continue;
      const double tilt = Tilt(state.q_WB);
      if (state.omega_B.norm() > kSettledRate_radps || tilt > kSettledTilt_rad) {
        last_unsettled_s = state.t_s;
      }
      if (t_hit == hit_times_s.front()) {
        response.t_s.push_back(state.t_s - t_hit);
        response.rate_radps.push_back(state.omega_B.norm());
        response.tilt_deg.push_back(tilt * 180.0 / kPi);
      }
    }
    response.settling_times_s.push_back(last_unsettled_s - t_hit);
  }
  return response;
}

struct TrackingResponse {
  double rate_rmse_radps = 0.0;        // RMS of |omega_des - omega| at the control steps
  double pitch_rate_rmse_radps = 0.0;  // RMS of e_omega_y
  double position_rmse_m = 0.0;        // E_a (F.39)
  double x_rmse_m = 0.0;               // RMS of e_x
  // Table G.1's statistics over the back-and-forth motions: mean and standard deviation of |e_x|
  // [m], of the thrust-direction error angle theta [rad] and of |e_omega_y| [rad/s].
  double x_error_mean_m = 0.0, x_error_std_m = 0.0;
  double thrust_angle_mean_rad = 0.0, thrust_angle_std_rad = 0.0;
  double pitch_rate_error_mean_radps = 0.0, pitch_rate_error_std_radps = 0.0;
  std::vector<double> t_s, pitch_rate_error_radps, x_error_m;
};

// Table G.1's theta: the angle between the thrust direction the position controller demands for
// the vehicle's true state and reference, z_des (the third column of R_des), and the body's z_B.
double ThrustDirectionError(const control::PositionController& controller,
                            const control::QuadState& state,
                            const control::TrajectoryPoint& reference) {
  const Eigen::Vector3d z_des_W = controller.Compute(state, reference).attitude.R_des_WB.col(2);
  const Eigen::Vector3d z_B_W = state.q_WB * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(z_des_W.dot(z_B_W), -1.0, 1.0));
}

// Back-and-forth flight of G.6.2 (Fig. G.6); the rate error compares each command's omega_des
// with the true rates at the time it is issued (both at the 100 Hz control steps).
TrackingResponse FlyBackAndForth(const BodyRateController& controller,
                                 const ControlBenchOptions& options) {
  control::BackAndForthTrajectoryParams reference;
  reference.start_W = Eigen::Vector3d(0.0, 0.0, kHoverHeight_m);
  if (options.quick) reference.num_round_trips = 1;
  sim::TrackingFlightParams params = BenchTrackingFlight(options);
  params.reference = std::make_shared<control::BackAndForthTrajectory>(reference);
  params.control.low_level = controller.params;
  params.control_rate_hz = kControlRate_hz;
  params.error_end_s = params.reference->EndTimeS();
  const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);

  TrackingResponse response;
  response.position_rmse_m = flight.error.E_a_m;
  response.x_rmse_m = flight.error.rmse_W_m.x();
  const std::vector<control::QuadState>& truth = flight.sitl.trajectory;
  const control::PositionController controller_W(params.dynamics.vehicle, params.control.position);
  std::vector<double> rate_errors, pitch_errors, abs_pitch_errors, abs_x_errors, thrust_angles;
  size_t k = 0;
  for (const sim::SitlCommandRecord& record : flight.sitl.commands) {
    if (record.t_s > params.error_end_s) break;
    while (k + 1 < truth.size() && truth[k + 1].t_s <= record.t_s + 1e-9) ++k;
    if (std::abs(truth[k].t_s - record.t_s) > 1e-6) continue;  // no ground truth at this step
    const Eigen::Vector3d e_B = record.command.thrust_rates.omega_des_B - truth[k].omega_B;
    const double e_x = truth[k].p_WB.x() - flight.reference[k].p_W.x();
    rate_errors.push_back(e_B.norm());
    pitch_errors.push_back(e_B.y());
    abs_pitch_errors.push_back(std::abs(e_B.y()));
    abs_x_errors.push_back(std::abs(e_x));
    thrust_angles.push_back(ThrustDirectionError(controller_W, truth[k], flight.reference[k]));
    response.t_s.push_back(record.t_s);
    response.pitch_rate_error_radps.push_back(e_B.y());
    response.x_error_m.push_back(e_x);
  }
  response.rate_rmse_radps = Rms(rate_errors);
  response.pitch_rate_rmse_radps = Rms(pitch_errors);
  response.x_error_mean_m = MeanOrZero(abs_x_errors);
  response.x_error_std_m = StandardDeviation(abs_x_errors);
  response.thrust_angle_mean_rad = MeanOrZero(thrust_angles);
  response.thrust_angle_std_rad = StandardDeviation(thrust_angles);
  response.pitch_rate_error_mean_radps = MeanOrZero(abs_pitch_errors);
  response.pitch_rate_error_std_radps = StandardDeviation(abs_pitch_errors);
  return response;
}

// Table G.1 of the thesis, per law (a) P low gain, (b) P high gain, (c) LQR, in its units.
struct ThesisG1Row {
  const char* statistic;  // as printed in the thesis
  const char* key;        // the body_rate figure
  double to_thesis_unit;  // SI -> the thesis' unit
  double a, b, c;
};
constexpr double kCm = 100.0;
constexpr double kDeg = 180.0 / kPi;
constexpr ThesisG1Row kTableG1[] = {
    {"mu(e_x) [cm]", "x_error_mean", kCm, 14.50, 9.39, 10.35},
    {"sigma(e_x) [cm]", "x_error_std", kCm, 23.05, 15.60, 17.19},
    {"mu(theta) [deg]", "thrust_angle_mean", kDeg, 5.55, 3.84, 4.14},
    {"sigma(theta) [deg]", "thrust_angle_std", kDeg, 7.33, 5.00, 5.22},
    {"mu(e_omega_y) [deg/s]", "pitch_rate_error_mean", kDeg, 42.28, 14.88, 21.52},
    {"sigma(e_omega_y) [deg/s]", "pitch_rate_error_std", kDeg, 72.38, 23.65, 32.41},
    {"mu(t_settle) [s]", "settling_time", 1.0, 0.42, 0.79, 0.41},
    {"sigma(t_settle) [s]", "settling_time_std", 1.0, 0.05, 0.09, 0.08},
};

// Rows of Table G.1 with this bench's values beside the thesis' (mean and standard deviation of
// |e_x|, theta, |e_omega_y| over every control step of the motions; of the settling times).
nlohmann::json TableG1(const nlohmann::json& body_rate) {
  nlohmann::json table = nlohmann::json::array();
  for (const ThesisG1Row& row : kTableG1) {
    nlohmann::json line = {{"statistic", row.statistic}};
    const std::pair<const char*, double> laws[] = {
        {"p_low", row.a}, {"p_high", row.b}, {"lqr", row.c}};
    const char* labels[] = {"(a)", "(b)", "(c)"};
    for (int i = 0; i < 3; ++i) {
      const auto& [law, thesis] = laws[i];
      line[std::string(labels[i])] = row.to_thesis_unit * body_rate[law][row.key].get<double>();
      line[std::string(labels[i]) + " thesis"] = thesis;
    }
    table.push_back(line);
  }
  return table;
}

void RunBodyRate(const ControlBenchOptions& options, nlohmann::json* summary,
                 output::HtmlReport* report) {
  report->AddSection("Body-rate control: P low gain, P high gain, LQR (Table G.1)");
  output::SvgPlot hit_rates({"Upward hit on one arm: body-rate magnitude (Fig. G.5 analog)",
                             "time since hit [s]", "|omega| [rad/s]"});
  output::SvgPlot hit_tilts({"Upward hit on one arm: tilt", "time since hit [s]", "tilt [deg]"});
  output::SvgPlot rate_errors({"Back-and-forth: pitch-rate error (Fig. G.7 analog)", "t [s]",
                               "omega_y,des - omega_y [rad/s]"});
  output::SvgPlot x_errors({"Back-and-forth: position error in x", "t [s]", "e_x [m]"});
  nlohmann::json& out = (*summary)["body_rate"];
  for (const BodyRateController& controller : BodyRateControllers(options)) {
    const TrackingResponse tracking = FlyBackAndForth(controller, options);
    out[controller.key]["rate_rmse"] = tracking.rate_rmse_radps;
    out[controller.key]["pitch_rate_rmse"] = tracking.pitch_rate_rmse_radps;
    out[controller.key]["position_rmse"] = tracking.position_rmse_m;
    out[controller.key]["x_rmse"] = tracking.x_rmse_m;
    out[controller.key]["x_error_mean"] = tracking.x_error_mean_m;
    out[controller.key]["x_error_std"] = tracking.x_error_std_m;
    out[controller.key]["thrust_angle_mean"] = tracking.thrust_angle_mean_rad;
    out[controller.key]["thrust_angle_std"] = tracking.thrust_angle_std_rad;
    out[controller.key]["pitch_rate_error_mean"] = tracking.pitch_rate_error_mean_radps;
    out[controller.key]["pitch_rate_error_std"] = tracking.pitch_rate_error_std_radps;
    rate_errors.AddLine(controller.label, tracking.t_s, tracking.pitch_rate_error_radps);
    x_errors.AddLine(controller.label, tracking.t_s, tracking.x_error_m);
    const HitResponse hits = FlyHits(controller, options);
    out[controller.key]["settling_time"] = MeanOrZero(hits.settling_times_s);
    out[controller.key]["settling_time_std"] = StandardDeviation(hits.settling_times_s);
    out[controller.key]["settling_time_max"] =
        *std::max_element(hits.settling_times_s.begin(), hits.settling_times_s.end());
    hit_rates.AddLine(controller.label, hits.t_s, hits.rate_radps);
    hit_tilts.AddLine(controller.label, hits.t_s, hits.tilt_deg);
  }
  const nlohmann::json table = TableG1(out);
  report->AddTable(table,
                   "Table G.1 analog: (a) P low gain, (b) P high gain, (c) LQR; thesis beside");
  out["table_g1"] = table;
  report->AddCollapsedTable(out, "body_rate figures (SI units)");
  report->AddSvg(rate_errors.Render(), "Pitch-rate error on the back-and-forth trajectory");
  report->AddSvg(x_errors.Render(), "Position error in x on the back-and-forth trajectory");
  report->AddSvg(hit_rates.Render(), "Body-rate magnitude after the first hit");
  report->AddSvg(hit_tilts.Render(), "Tilt after the first hit");
}

// ---------------------------------------------------------------------------------------------
// mixer

// G.6.3 isolates the mixer in an indoor hover; what makes a real hover need unequal thrusts is
// the vehicle's imbalance. Here: the centre of mass 1 cm off the rotor centre in x and y (a
// battery strap's worth), i.e. gravity's torque r_B x (-m g z_B), held by roll and pitch torques
// of ~0.044 N m (rotor 3 at ~0.93, rotor 1 at ~1.28 of hover thrust).
Eigen::Vector3d CentreOfMassOffsetTorque(const control::VehicleParameters& vehicle) {
  const Eigen::Vector3d r_B(0.01, 0.01, 0.0);
  return r_B.cross(Eigen::Vector3d(0.0, 0.0, -vehicle.mass_kg * vehicle.gravity_mps2));
}

// The offset torque acts from t = 0 on a vehicle started with equal thrusts: statistics begin
// once that transient has decayed (attitude and position loops: < 1 s time constants).
constexpr double kMixerSettle_s = 5.0;

struct YawTrace {
  std::vector<double> t_s, yaw_error_rad;
};

YawTrace FlyMixerHover(control::MixerParameters::Mixing mixing, const ControlBenchOptions& options,
                       double duration_s) {
  sim::SitlRunnerParams params =
      BenchRunParams(options, duration_s, Eigen::Vector3d(0.0, 0.0, kHoverHeight_m));
  params.flight_controller.low_level.mixer.mixing = mixing;
  params.disturbances.torque_B_Nm = CentreOfMassOffsetTorque(params.dynamics.vehicle);
  const sim::SitlResult result = FlyHover(params, options);
  const control::PositionController controller(params.dynamics.vehicle);
  control::TrajectoryPoint hover;
  hover.p_W = params.initial_state.p_WB;  // heading 0
  YawTrace trace;
  for (const control::QuadState& state : result.trajectory) {
    if (state.t_s < kMixerSettle_s) continue;
    trace.t_s.push_back(state.t_s);
    trace.yaw_error_rad.push_back(HeadingError(controller, state, hover));
  }
  return trace;
}

void RunMixer(const ControlBenchOptions& options, nlohmann::json* summary,
              output::HtmlReport* report) {
  const double duration_s = options.quick ? 20.0 : 180.0;  // Table G.2: three minutes
  const YawTrace iterative =
      FlyMixerHover(control::MixerParameters::Mixing::kIterative, options, duration_s);
  const YawTrace one_shot =
      FlyMixerHover(control::MixerParameters::Mixing::kOneShot, options, duration_s);
  nlohmann::json& out = (*summary)["mixer"];
  out["duration"] = duration_s;
  out["yaw_rmse_iterative"] = Rms(iterative.yaw_error_rad);
  out["yaw_rmse_one_shot"] = Rms(one_shot.yaw_error_rad);
  out["yaw_max_iterative"] = MaxAbs(iterative.yaw_error_rad);
  out["yaw_max_one_shot"] = MaxAbs(one_shot.yaw_error_rad);
  out["yaw_rmse_reduction"] = 1.0 - Rms(iterative.yaw_error_rad) / Rms(one_shot.yaw_error_rad);

  report->AddSection("Iterative vs one-shot mixer in hover (Table G.2)");
  report->AddTable(out, "mixer figures (SI units, yaw in rad)");
  // Plotted at 10 Hz in degrees (the statistics use every 100 Hz sample).
  auto decimate = [](const std::vector<double>& v, double scale) {
    std::vector<double> out;
    for (size_t i = 0; i < v.size(); i += 10) out.push_back(scale * v[i]);
    return out;
  };
  output::SvgPlot plot({"Yaw error in hover (Fig. G.8 analog)", "t [s]", "yaw error [deg]"});
  plot.AddLine("one-shot", decimate(one_shot.t_s, 1.0),
               decimate(one_shot.yaw_error_rad, 180.0 / kPi));
  plot.AddLine("iterative", decimate(iterative.t_s, 1.0),
               decimate(iterative.yaw_error_rad, 180.0 / kPi));
  report->AddSvg(plot.Render(), "Yaw error (desired heading 0) with each mixer");
}

// ---------------------------------------------------------------------------------------------
// saturation

constexpr double kStepTime_s = 3.0;  // after the imbalance transient (as kMixerSettle_s)
constexpr double kStepStartHeight_m = 1.0;
constexpr double kAssuredYawTorque_Nm = 0.01;  // eta_z,assured of Fig. G.9

struct SaturationFlight {
  double xy_max_dev_m = 0.0;
  bool crashed = false;
  double yaw_settling_time_s = 0.0;  // until |yaw - 90 deg| stays below 5 deg
  std::vector<double> t_s, xy_dev_m, height_m, yaw_deg;
};

SaturationFlight FlySaturationStep(control::MixerParameters::Saturation saturation,
                                   const ControlBenchOptions& options) {
  // The bench vehicle first: the thrust limits below are the true rotors' (as far as the flight
  // controller's model, hover-calibrated, knows them).
  sim::SitlRunnerParams params =
      WithBenchVehicle(BenchRunParams(options, kStepTime_s + (options.quick ? 4.0 : 6.0),
                                      Eigen::Vector3d(0.0, 0.0, kStepStartHeight_m)),
                       options);
  // G.6.4: single-rotor thrust limited to 0.8 / 1.6 N around 1.25 N hover: the same fractions of
  // our hover thrust, imposed through the motor command range (flight controller and motors).
  control::VehicleParameters& model =
      params.flight_controller_model ? *params.flight_controller_model : params.dynamics.vehicle;
  const double hover_thrust_N = 0.25 * model.mass_kg * model.gravity_mps2;
  const double min_command = model.rotor.CommandFromThrust(0.8 / 1.25 * hover_thrust_N);
  const double max_command = model.rotor.CommandFromThrust(1.6 / 1.25 * hover_thrust_N);
  for (control::VehicleParameters* vehicle : {&model, &params.dynamics.vehicle}) {
    vehicle->rotor.command_min = min_command;
    vehicle->rotor.command_max = max_command;
  }
  params.flight_controller.low_level.mixer.saturation = saturation;
  params.flight_controller.low_level.mixer.assured_yaw_torque_Nm = kAssuredYawTorque_Nm;
  // The same imbalance as in the mixer hover: holding attitude needs roll and pitch torques,
  // which clipping gives up while saturated.
  params.disturbances.torque_B_Nm = CentreOfMassOffsetTorque(model);

  sim::GroundTruthAutopilotParams autopilot_params = BenchAutopilot(options);
  const Eigen::Vector3d start_W = params.initial_state.p_WB;
  // Hover until the imbalance transient has decayed, then the step (time-triggered: the arrival
  // radius is far larger than the transient's excursion of ~0.2 m).
  autopilot_params.waypoints.push_back({start_W, 0.0, kStepTime_s});
  autopilot_params.waypoints.push_back({start_W + Eigen::Vector3d(0.0, 0.0, 1.0), kPi / 2, 0.0});
  autopilot_params.arrival_radius_m = 0.5;
  sim::GroundTruthAutopilot autopilot(model, autopilot_params);
  sim::SitlRunner runner(params, nullptr);
  const sim::SitlResult result = runner.Run(autopilot);

  SaturationFlight flight;
  flight.crashed = result.outcome == sim::SitlResult::Outcome::kCollision;
  // Deviation from where the vehicle hovered when the step was commanded.
  Eigen::Vector3d hover_W = start_W;
  for (const control::QuadState& state : result.trajectory) {
    if (state.t_s <= kStepTime_s + 0.5 / kControlRate_hz) hover_W = state.p_WB;
  }
  double yaw_unsettled_s = kStepTime_s;
  for (const control::QuadState& state : result.trajectory) {
    const double xy_dev = state.t_s < kStepTime_s ? 0.0 : (state.p_WB - hover_W).head<2>().norm();
    flight.xy_max_dev_m = std::max(flight.xy_max_dev_m, xy_dev);
    const double yaw = Yaw(state.q_WB);
    if (std::abs(WrapAngle(yaw - kPi / 2)) > 5.0 * kPi / 180.0) yaw_unsettled_s = state.t_s;
    flight.t_s.push_back(state.t_s);
    flight.xy_dev_m.push_back(xy_dev);
    flight.height_m.push_back(state.p_WB.z());
    flight.yaw_deg.push_back(yaw * 180.0 / kPi);
  }
  flight.yaw_settling_time_s = yaw_unsettled_s - kStepTime_s;
  return flight;
}

void RunSaturation(const ControlBenchOptions& options, nlohmann::json* summary,
                   output::HtmlReport* report) {
  using Saturation = control::MixerParameters::Saturation;
  report->AddSection("Prioritized saturation vs clipping: 1 m climb + 90 deg yaw step (G.6.4)");
  output::SvgPlot xy({"Horizontal deviation (Fig. G.9 analog)", "t [s]", "xy deviation [m]"});
  output::SvgPlot height({"Height", "t [s]", "z [m]"});
  output::SvgPlot yaw({"Yaw", "t [s]", "yaw [deg]"});
  nlohmann::json& out = (*summary)["saturation"];
  out["assured_yaw_torque"] = kAssuredYawTorque_Nm;
  for (const auto& [key, saturation] :
       {std::pair{"prioritized", Saturation::kPrioritized}, {"clipping", Saturation::kClip}}) {
    const SaturationFlight flight = FlySaturationStep(saturation, options);
    out[key]["xy_max_dev"] = flight.xy_max_dev_m;
    out[key]["crashed"] = flight.crashed;
    out[key]["yaw_settling_time"] = flight.yaw_settling_time_s;
    xy.AddLine(key, flight.t_s, flight.xy_dev_m);
    height.AddLine(key, flight.t_s, flight.height_m);
    yaw.AddLine(key, flight.t_s, flight.yaw_deg);
  }
  report->AddTable(out, "saturation figures (SI units)");
  report->AddSvg(xy.Render(), "Distance from the hover point in x-y; the step is at t = 3 s");
  report->AddSvg(height.Render(), "Height (step 1 m -> 2 m)");
  report->AddSvg(yaw.Render(), "Yaw (step 0 -> 90 deg): prioritized saturation gives it up first");
}

}  // namespace

ControlBenchSection MakeBodyRateSection() { return {"body_rate", RunBodyRate}; }
ControlBenchSection MakeMixerSection() { return {"mixer", RunMixer}; }
ControlBenchSection MakeSaturationSection() { return {"saturation", RunSaturation}; }

}  // namespace aperture::experiments
