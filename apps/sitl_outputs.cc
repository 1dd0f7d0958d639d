#include "apps/sitl_outputs.h"

#include <string>
#include <vector>

#include "apps/imu_csv.h"
#include "experiments/bench/sitl_profile_json.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"
#include "output/tum_trajectory_writer.h"

namespace aperture::apps {

void WriteSitlTimeSeries(const sim::SitlResult& result, output::OutputFolder& out) {
  output::CsvWriter trajectory(
      out.Path("trajectory.csv"),
      {"t_s", "p_x_m", "p_y_m", "p_z_m", "v_x_mps", "v_y_mps", "v_z_mps", "q_w", "q_x", "q_y",
       "q_z", "omega_x_radps", "omega_y_radps", "omega_z_radps"});
  output::TumTrajectoryWriter tum(out.Path("trajectory.tum"));
  for (const control::QuadState& s : result.trajectory) {
    trajectory.WriteRow({s.t_s, s.p_WB.x(), s.p_WB.y(), s.p_WB.z(), s.v_W.x(), s.v_W.y(), s.v_W.z(),
                         s.q_WB.w(), s.q_WB.x(), s.q_WB.y(), s.q_WB.z(), s.omega_B.x(),
                         s.omega_B.y(), s.omega_B.z()});
    tum.Write(s.t_s, s.p_WB, s.q_WB);
  }
  trajectory.Close();
  tum.Close();
  output::CsvWriter commands(
      out.Path("commands.csv"),
      {"t_s", "kind", "collective_thrust_mps2", "omega_des_x_radps", "omega_des_y_radps",
       "omega_des_z_radps", "rotor1_N", "rotor2_N", "rotor3_N", "rotor4_N"});
  for (const sim::SitlCommandRecord& record : result.commands) {
    const perception::AutopilotCommand& c = record.command;
    const char* kind = c.kind == perception::AutopilotCommand::Kind::kThrustRates ? "thrust_rates"
                       : c.kind == perception::AutopilotCommand::Kind::kRotorThrusts
                           ? "rotor_thrusts"
                           : "none";
    const Eigen::Vector4d& f = record.rotor_thrusts_N;
    commands.WriteCells({record.t_s, std::string(kind), c.thrust_rates.collective_thrust_mps2,
                         c.thrust_rates.omega_des_B.x(), c.thrust_rates.omega_des_B.y(),
                         c.thrust_rates.omega_des_B.z(), f(0), f(1), f(2), f(3)});
  }
  commands.Close();
  const std::unique_ptr<output::CsvWriter> imu = MakeImuCsv(out.Path("imu.csv"));
  for (const perception::ImuSample& sample : result.imu) WriteImuRow(*imu, sample);
  imu->Close();
}

void AddSitlCommandPlots(const sim::SitlResult& result, output::HtmlReport* report) {
  std::vector<double> tc, thrust, wx, wy, wz;
  std::vector<std::vector<double>> rotors(4);
  for (const sim::SitlCommandRecord& record : result.commands) {
    tc.push_back(record.t_s);
    thrust.push_back(record.command.thrust_rates.collective_thrust_mps2);
    wx.push_back(record.command.thrust_rates.omega_des_B.x());
    wy.push_back(record.command.thrust_rates.omega_des_B.y());
    wz.push_back(record.command.thrust_rates.omega_des_B.z());
    for (int i = 0; i < 4; ++i) rotors[i].push_back(record.rotor_thrusts_N(i));
  }
  report->AddSection("Commands");
  report->AddSvg(output::SvgPlot({"Collective thrust command", "t [s]", "c [m/s^2]"})
                     .AddLine("c_cmd", tc, thrust)
                     .Render());
  report->AddSvg(output::SvgPlot({"Body-rate command", "t [s]", "omega_des [rad/s]"})
                     .AddLine("p", tc, wx)
                     .AddLine("q", tc, wy)
                     .AddLine("r", tc, wz)
                     .Render());
  output::SvgPlot rotor_plot({"Rotor thrusts (flight controller)", "t [s]", "f [N]"});
  for (int i = 0; i < 4; ++i) rotor_plot.AddLine("f" + std::to_string(i + 1), tc, rotors[i]);
  report->AddSvg(rotor_plot.Render());
}

void AddSitlRunSummary(const sim::SitlResult& result, nlohmann::json* summary) {
  (*summary)["outcome"] = sim::ToString(result.outcome);
  (*summary)["reason"] = result.reason;
  (*summary)["sim_time_s"] = result.sim_time_s;
  (*summary)["real_time_factor"] = result.real_time_factor;
  // The data rows of WriteSitlTimeSeries' files (the flight so far when it was stopped).
  (*summary)["rows"] = {{"trajectory", result.trajectory.size()},
                        {"commands", result.commands.size()},
                        {"imu", result.imu.size()}};
  (*summary)["timing"] = {
      {"wall_time_s", result.timing.wall_time_s},
      {"dynamics_s", result.timing.dynamics_s},
      {"render_s", result.timing.render_s},
      {"autopilot_s", result.timing.autopilot_s},
      {"collision_s", result.timing.collision_s},
      {"hooks_s", result.timing.hooks_s},
      {"cpu", experiments::SitlCpuProfileToJson(result.timing.cpu, result.sim_time_s)}};
}

}  // namespace aperture::apps
