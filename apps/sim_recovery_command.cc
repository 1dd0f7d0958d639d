// aperture sim recovery: a seeded hand throw recovered by the on-board pipeline of Faessler thesis
// paper B (launch detection B.29, IMU attitude estimator, height filter, five-stage state machine
// B.3.2) in the SITL, from the simulated IMU and range sensor (vision emulated, see
// sim/sitl/recovery_autopilot.h).
//
//   aperture sim recovery [--seed N] [--duration S] [--set control.body_rate=p_low ...]
//       [--config FILE] --out DIR
//
// --seed draws the throw (attitude up to upside-down, several m/s, tumbling; SampleHandThrow) and
// the sensor noise. Config sections: control (the flight controller's body-rate law, mixer,
// saturation), dynamics, imu, range. Writes OUT/summary.json (recovery.outcome = recovered |
// crashed | timeout, recovery.stage_times_s, the throw, final tilt and speed), OUT/stages.csv,
// trajectory.csv/.tum, commands.csv, imu.csv and OUT/report.html (height, tilt, speed with the
// stage transitions, commands). No camera is flown, so there is no video.
#include <cmath>
#include <iostream>
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/sitl_outputs.h"
#include "control/constants.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/json_eigen.h"
#include "output/svg_plot.h"
#include "sim/control_params_io.h"
#include "sim/sim_params_io.h"
#include "sim/sitl/recovery_flight.h"

namespace aperture::apps {
namespace {

using control::kRadToDeg;

struct RecoveryOptions {
  CommonOptions common;
  std::uint64_t seed = 1;
  double duration_s = 10.0;
};

double TiltRad(const Eigen::Quaterniond& q_WB) {
  return std::acos(std::clamp((q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
}

void WriteRecoveryReport(const sim::RecoveryFlightResult& flight, output::OutputFolder& out) {
  output::HtmlReport report("aperture sim recovery");
  report.AddSection("Summary");
  report.AddTable(out.summary());
  std::vector<double> t, height, tilt_deg, speed;
  for (const control::QuadState& s : flight.sitl.trajectory) {
    t.push_back(s.t_s);
    height.push_back(s.p_WB.z());
    tilt_deg.push_back(TiltRad(s.q_WB) * kRadToDeg);
    speed.push_back(s.v_W.norm());
  }
  // Stage transitions as markers on each plot's zero line.
  std::vector<double> t_stage, zero;
  for (const control::RecoveryTransition& transition : flight.transitions) {
    t_stage.push_back(transition.t_s);
    zero.push_back(0.0);
  }
  report.AddSection("Flight (ground truth; markers: stage transitions B.3.2)");
  report.AddSvg(output::SvgPlot({"Height", "t [s]", "z [m]"})
                    .AddLine("z", t, height)
                    .AddScatter("stage entry", t_stage, zero)
                    .Render());
  report.AddSvg(output::SvgPlot({"Tilt (angle between z_B and z_W)", "t [s]", "[deg]"})
                    .AddLine("tilt", t, tilt_deg)
                    .AddScatter("stage entry", t_stage, zero)
                    .Render());
  report.AddSvg(output::SvgPlot({"Speed", "t [s]", "|v| [m/s]"})
                    .AddLine("speed", t, speed)
                    .AddScatter("stage entry", t_stage, zero)
                    .Render());
  AddSitlCommandPlots(flight.sitl, &report);
  report.Write(out.Path("report.html"));
}

void RunRecovery(const RecoveryOptions& options, output::OutputFolder& out) {
  config::ConfigTree tree = LoadConfig(options.common, "");
  config::ParamReader root = tree.Reader();
  sim::RecoveryFlightParams params;
  root.ReadSection("control", &params.control);
  root.ReadSection("dynamics", &params.dynamics);
  root.ReadSection("imu", &params.imu);
  root.ReadSection("range", &params.range);
  root.RejectUnknownKeys();
  params.hand_throw = sim::SampleHandThrow(options.seed);
  params.seed = options.seed;
  params.duration_s = options.duration_s;
  params.trajectory_decimation = 5;  // 200 Hz ground truth in the outputs
  const sim::RecoveryFlightResult flight = sim::FlyRecoveryFlight(params);

  nlohmann::json& summary = out.summary();
  summary["command"] = "sim recovery";
  summary["inputs"] = {{"seed", options.seed},
                       {"duration_s", options.duration_s},
                       {"autopilot", flight.sitl.autopilot_name}};
  tree.PutParams("control", params.control);
  tree.PutParams("dynamics", params.dynamics);
  tree.PutParams("imu", params.imu);
  tree.PutParams("range", params.range);
  summary["config"] = nlohmann::json::parse(tree.ToJson());
  summary["throw"] = {{"tilt_deg", TiltRad(params.hand_throw.q_WB) * kRadToDeg},
                      {"v_W_mps", output::EigenToJson(params.hand_throw.v_W)},
                      {"omega_B_radps", output::EigenToJson(params.hand_throw.omega_B)},
                      {"p_release_W_m", output::EigenToJson(params.p_release_W)}};
  AddSitlRunSummary(flight.sitl, &summary);
  nlohmann::json stage_times = nlohmann::json::object();
  output::CsvWriter stages(out.Path("stages.csv"), {"t_s", "from", "to"});
  for (const control::RecoveryTransition& transition : flight.transitions) {
    stage_times[control::ToString(transition.to)] = transition.t_s;
    stages.WriteCells({transition.t_s, std::string(control::ToString(transition.from)),
                       std::string(control::ToString(transition.to))});
  }
  stages.Close();
  summary["recovery"] = {{"outcome", flight.outcome},
                         {"stage_times_s", stage_times},
                         {"vision_available_s", flight.vision_available_s},
                         {"min_height_m", flight.min_height_m},
                         {"final_tilt_deg", flight.final_tilt_rad * kRadToDeg},
                         {"final_speed_mps", flight.final_speed_mps}};
  WriteSitlTimeSeries(flight.sitl, out);
  summary["outputs"] = {{"stages", "stages.csv"},  {"trajectory", "trajectory.csv"},
                        {"tum", "trajectory.tum"}, {"commands", "commands.csv"},
                        {"imu", "imu.csv"},        {"report", "report.html"}};
  WriteRecoveryReport(flight, out);
  std::cout << "aperture sim recovery (seed " << options.seed << "): " << flight.outcome
            << " after " << flight.sitl.sim_time_s << " s (" << flight.sitl.reason << ")\n";
}

}  // namespace

void AddSimRecoveryCommand(CLI::App& sim, int* exit_code) {
  auto options = std::make_shared<RecoveryOptions>();
  CLI::App* command = sim.add_subcommand(
      "recovery", "Recover a seeded hand throw with the on-board pipeline of thesis paper B");
  AddSeedOption(command, &options->seed, "Seed of the throw and every sensor stream");
  command->add_option("--duration", options->duration_s, "Timeout [s]")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunRecovery(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
