#pragma once
// Subcommands of the `aperture` executable. Each Add*Command registers its CLI11 subcommand and
// stores its exit code in *exit_code when it runs. Apps stay thin (STYLE.md 10): parse, build
// library objects, run, report.
#include <CLI/CLI.hpp>

namespace aperture::apps {

void AddRunCommand(CLI::App& app, int* exit_code);
void AddSimCommand(CLI::App& app, int* exit_code);
void AddRenderCommand(CLI::App& app, int* exit_code);
void AddBenchCommand(CLI::App& app, int* exit_code);
void AddBenchLedCommand(CLI::App& bench, int* exit_code);
void AddCalibrateCommand(CLI::App& app, int* exit_code);
void AddTrainCommand(CLI::App& app, int* exit_code);
void AddVersionCommand(CLI::App& app, int* exit_code);

// Flows under `aperture sim` (apps/sim_<flow>_command.cc).
void AddSimTrackingCommand(CLI::App& sim, int* exit_code);
void AddSimRecoveryCommand(CLI::App& sim, int* exit_code);

// Benchmarks under `aperture bench` (apps/bench_<name>_command.cc).
void AddBenchControlCommand(CLI::App& bench, int* exit_code);
void AddBenchDeliveryCommand(CLI::App& bench, int* exit_code);
void AddBenchFaultsCommand(CLI::App& bench, int* exit_code);
void AddBenchGapCommand(CLI::App& bench, int* exit_code);
void AddBenchGapflytCommand(CLI::App& bench, int* exit_code);
// `aperture bench merge`: the shards of any Monte-Carlo bench (apps/monte_carlo_command.h).
void AddBenchMergeCommand(CLI::App& bench, int* exit_code);
void AddBenchMononavCommand(CLI::App& bench, int* exit_code);
void AddBenchSoakCommand(CLI::App& bench, int* exit_code);
void AddBenchTs2pCommand(CLI::App& bench, int* exit_code);
void AddBenchTagsCommand(CLI::App& bench, int* exit_code);

}  // namespace aperture::apps
