#pragma once
// Outputs every `aperture sim` flow writes from a SITL run (scenario, tracking, recovery).
#include "output/html_report.h"
#include "output/output_folder.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::apps {

// OUT/trajectory.csv and OUT/trajectory.tum (ground truth), OUT/commands.csv (autopilot commands
// and flight-controller rotor thrusts), OUT/imu.csv (IMU samples as delivered).
void WriteSitlTimeSeries(const sim::SitlResult& result, output::OutputFolder& out);

// A "Commands" section: collective thrust and body-rate commands, rotor thrusts.
void AddSitlCommandPlots(const sim::SitlResult& result, output::HtmlReport* report);

// summary["sim_time_s"], ["real_time_factor"], ["timing"] (SitlTiming: wall_time_s, dynamics_s,
// render_s, autopilot_s, collision_s, hooks_s), ["outcome"], ["reason"], ["rows"] (data rows
// of trajectory.csv, commands.csv, imu.csv).
void AddSitlRunSummary(const sim::SitlResult& result, nlohmann::json* summary);

}  // namespace aperture::apps
