// aperture sim tracking: fly a thesis reference trajectory on ground truth (the motion-capture
// experiments of Faessler thesis F.7 and G.6) through the full control stack in the SITL.
//
//   aperture sim tracking --trajectory circle|lemniscate|back_and_forth|ramp|lemniscate_ramp
//       [--set control.drag_compensation=true|false] [--set control.body_rate=lqr|p_low|p_high]
//       [--set control.mixer=iterative|one_shot] [--set control.saturation=prioritized|clipping]
//       [--config FILE] [--seed N] [--duration S] --out DIR
//
// Config sections: control (sim/control_params_io.h), dynamics (the simulated vehicle,
// sim/sim_params_io.h), imu. The vehicle starts hovering at the reference's start; `ramp` is the
// F.7 circle speed ramp 0 -> 5 m/s in 30 s (32 s flown unless --duration). Writes OUT/summary.json
// (tracking.E_a_m of F.39, max and per-axis RMSE over the whole flight; outcome, timing),
// OUT/tracking.csv (ground truth beside the reference), trajectory.csv/.tum, commands.csv,
// imu.csv and OUT/report.html (x-y path, position and error over time, commands). No camera is
// flown, so there is no video.
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/sitl_outputs.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/json_eigen.h"
#include "output/svg_plot.h"
#include "sim/control_params_io.h"
#include "sim/sim_params_io.h"
#include "sim/sitl/tracking_flight.h"

namespace aperture::apps {
namespace {

// Command-line name -> control::MakeThesisTrajectory name.
const std::map<std::string, std::string> kTrajectories = {
    {"circle", "circle"},
    {"lemniscate", "lemniscate"},
    {"back_and_forth", "back_and_forth"},
    {"ramp", "circle_speed_ramp"},
    {"lemniscate_ramp", "lemniscate_speed_ramp"}};
constexpr double kRampDurationS = 32.0;  // F.7: full speed (5 m/s) reached at 30 s

constexpr const char* kDefaultsYaml = R"(control:
  drag_compensation: true
  body_rate: lqr
  mixer: iterative
  saturation: prioritized
)";

struct TrackingOptions {
  CommonOptions common;
  std::string trajectory = "circle";
  std::uint64_t seed = 1;
  std::optional<double> duration_s;
};

void WriteTrackingCsv(const sim::TrackingFlightResult& flight, output::OutputFolder& out) {
  output::CsvWriter csv(
      out.Path("tracking.csv"),
      {"t_s", "p_x_m", "p_y_m", "p_z_m", "p_ref_x_m", "p_ref_y_m", "p_ref_z_m", "v_x_mps",
       "v_y_mps", "v_z_mps", "v_ref_x_mps", "v_ref_y_mps", "v_ref_z_mps", "error_m"});
  for (size_t k = 0; k < flight.sitl.trajectory.size(); ++k) {
    const control::QuadState& s = flight.sitl.trajectory[k];
    const control::TrajectoryPoint& r = flight.reference[k];
    csv.WriteRow({s.t_s, s.p_WB.x(), s.p_WB.y(), s.p_WB.z(), r.p_W.x(), r.p_W.y(), r.p_W.z(),
                  s.v_W.x(), s.v_W.y(), s.v_W.z(), r.v_W.x(), r.v_W.y(), r.v_W.z(),
                  (s.p_WB - r.p_W).norm()});
  }
  csv.Close();
}

void WriteTrackingReport(const sim::TrackingFlightResult& flight, const std::string& title,
                         output::OutputFolder& out) {
  output::HtmlReport report(title);
  report.AddSection("Summary");
  report.AddTable(out.summary());
  std::vector<double> t, error;
  std::vector<std::vector<double>> p(3), p_ref(3);
  for (size_t k = 0; k < flight.sitl.trajectory.size(); ++k) {
    const control::QuadState& s = flight.sitl.trajectory[k];
    t.push_back(s.t_s);
    error.push_back((s.p_WB - flight.reference[k].p_W).norm());
    for (int i = 0; i < 3; ++i) {
      p[i].push_back(s.p_WB(i));
      p_ref[i].push_back(flight.reference[k].p_W(i));
    }
  }
  report.AddSection("Tracking (ground truth vs reference)");
  report.AddSvg(output::SvgPlot({"x-y path", "x [m]", "y [m]"})
                    .AddLine("reference", p_ref[0], p_ref[1])
                    .AddLine("flown", p[0], p[1])
                    .Render());
  output::SvgPlot position({"Position", "t [s]", "p [m]"});
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    position.AddLine(std::string(axes[i]) + " ref", t, p_ref[i]).AddLine(axes[i], t, p[i]);
  }
  report.AddSvg(position.Render());
  report.AddSvg(output::SvgPlot({"Position error |p - p_ref| (E_p of F.39)", "t [s]", "[m]"})
                    .AddLine("error", t, error)
                    .Render());
  AddSitlCommandPlots(flight.sitl, &report);
  report.Write(out.Path("report.html"));
}

void RunTracking(const TrackingOptions& options, output::OutputFolder& out) {
  config::ConfigTree tree = LoadConfig(options.common, kDefaultsYaml);
  config::ParamReader root = tree.Reader();
  sim::TrackingFlightParams params;
  root.ReadSection("control", &params.control);
  root.ReadSection("dynamics", &params.dynamics);
  root.ReadSection("imu", &params.imu);
  root.RejectUnknownKeys();
  params.reference = control::MakeThesisTrajectory(kTrajectories.at(options.trajectory));
  params.seed = options.seed;
  if (options.duration_s) {
    params.duration_s = *options.duration_s;
  } else if (!std::isfinite(params.reference->EndTimeS())) {
    params.duration_s = kRampDurationS;
  }
  params.trajectory_decimation = 5;  // 200 Hz ground truth in the outputs
  const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);

  nlohmann::json& summary = out.summary();
  summary["command"] = "sim tracking";
  summary["inputs"] = {{"trajectory", options.trajectory},
                       {"seed", options.seed},
                       {"autopilot", flight.sitl.autopilot_name}};
  tree.PutParams("control", params.control);
  tree.PutParams("dynamics", params.dynamics);
  tree.PutParams("imu", params.imu);
  summary["config"] = nlohmann::json::parse(tree.ToJson());
  summary["control"] = {{"drag_compensation", params.control.position.compensate_rotor_drag},
                        {"body_rate", sim::BodyRateName(params.control.low_level)},
                        {"mixer", sim::ToString(params.control.low_level.mixer.mixing)},
                        {"saturation", sim::ToString(params.control.low_level.mixer.saturation)}};
  AddSitlRunSummary(flight.sitl, &summary);
  summary["tracking"] = {{"E_a_m", flight.error.E_a_m},
                         {"max_error_m", flight.error.max_m},
                         {"rmse_W_m", output::EigenToJson(flight.error.rmse_W_m)},
                         {"samples", flight.error.samples}};
  WriteTrackingCsv(flight, out);
  WriteSitlTimeSeries(flight.sitl, out);
  summary["outputs"] = {{"tracking", "tracking.csv"}, {"trajectory", "trajectory.csv"},
                        {"tum", "trajectory.tum"},    {"commands", "commands.csv"},
                        {"imu", "imu.csv"},           {"report", "report.html"}};
  WriteTrackingReport(flight, "aperture sim tracking: " + options.trajectory, out);
  std::cout << "aperture sim tracking " << options.trajectory << ": E_a = " << flight.error.E_a_m
            << " m, max " << flight.error.max_m << " m over " << flight.sitl.sim_time_s << " s ("
            << sim::ToString(flight.sitl.outcome) << ")\n";
}

}  // namespace

void AddSimTrackingCommand(CLI::App& sim, int* exit_code) {
  auto options = std::make_shared<TrackingOptions>();
  CLI::App* command = sim.add_subcommand(
      "tracking", "Fly a thesis reference trajectory on ground truth through the control stack");
  std::vector<std::string> names;
  for (const auto& [name, unused] : kTrajectories) names.push_back(name);
  command->add_option("--trajectory", options->trajectory, "Reference trajectory")
      ->check(CLI::IsMember(names));
  AddSeedOption(command, &options->seed, "Seed of every sensor stream");
  command
      ->add_option("--duration", options->duration_s,
                   "Simulated time [s] (default: the reference's end + 1 s; ramp: 32 s)")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunTracking(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
