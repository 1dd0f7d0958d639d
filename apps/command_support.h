#pragma once
// What every aperture command shares: the --out/--overwrite/--config/--set options, the checks of
// --seed and of number options. Commands run their body through output::RunAndWriteSummary, so a
// run either finishes with status "ok" or leaves summary.json with status "failed" and the error
// (which main() prints, exiting with 2 for a usage error, config::UsageError, else 1).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "output/output_folder.h"

namespace aperture::sim {
struct ScenarioParams;
}  // namespace aperture::sim

namespace aperture::apps {

struct CommonOptions {
  std::string out_dir;
  bool overwrite = false;                 // --overwrite: replace an earlier run's outputs
  std::vector<std::string> config_files;  // --config FILE (repeatable, in order)
  std::vector<std::string> set_items;     // --set key=value (repeatable, in order)
};

// Adds --out (required), --overwrite, --config and --set to `command`.
void AddCommonOptions(CLI::App* command, CommonOptions* options);
// Adds --overwrite (for commands with their own --out option).
void AddOverwriteFlag(CLI::App* command, bool* overwrite);
// The --out folder (output::OutputFolder): a folder holding an earlier run's outputs is a usage
// error (config::UsageError, exit 2) unless `overwrite`.
output::OutputFolder OpenOutputFolder(const std::string& out_dir, bool overwrite);
inline output::OutputFolder OpenOutputFolder(const CommonOptions& options) {
  return OpenOutputFolder(options.out_dir, options.overwrite);
}

// The one seed rule of every command: --seed is an unsigned 64-bit integer written in decimal
// digits, 0 to 18446744073709551615; anything else ("-1", "1e3", 2^64) is a usage error (exit 2),
// never wrapped or clamped. summary.json records it exactly (a JSON integer).
CLI::Option* AddSeedOption(CLI::App* command, std::uint64_t* seed, const std::string& description);
CLI::Option* AddSeedOption(CLI::App* command, std::optional<std::uint64_t>* seed,
                           const std::string& description);
// The same rule for another seed option (e.g. sim's --fault-seed).
CLI::Validator SeedValidator();
// The check of a number option: finite and in [min, max] (CLI11's own number checks pass nan and
// inf); the error prints the bounds readably ("in (0, 1e+06]").
CLI::Validator FiniteNumberIn(double min, double max, bool min_inclusive = true);
// The check of a count option (--frames, --trials, --threads, ...): an integer in decimal digits in
// [min, max]; CLI11's PositiveNumber would print its bound as a 309-digit number and let a value
// beyond int through to a "Could not convert". The error and the help show "INT in [1, 64]" (or
// "INT >= 1" when `max` is the largest int).
CLI::Validator IntegerIn(long long min, long long max = std::numeric_limits<int>::max());
// The check of a comma-separated list option (--laws moments,pid): every item one of `allowed`;
// a typo is a usage error listing them.
CLI::Validator CommaListOf(const std::vector<std::string>& allowed);
// The longest simulated time of a --duration [s]: 10 days.
inline constexpr double kMaxDurationS = 864000.0;
// --fps of a frame source without timestamps [Hz]: one frame per 1000 s to 10 kHz.
inline constexpr double kMinFps = 1e-3;
inline constexpr double kMaxFps = 1e4;

// The built-in scenarios' names, comma-separated ("forest, gap, ...").
std::string BuiltinScenarioList();

// A built-in scenario's name (the NAME of sim and render): a missing or unknown one is a usage
// error (config::UsageError) listing the built-in scenarios.
void RequireBuiltinScenario(const std::string& name);

// Records the LEDs a `led` scenario really renders (those of the led.config file when one is
// given) as led.leds of `tree`, so summary.json "config" shows them rather than the built-in
// ones; other scenarios are left alone.
void PutEffectiveLeds(const sim::ScenarioParams& params, config::ConfigTree* tree);

// Runs `check` (e.g. the Validate of parameters assembled from `tree` and the options): an
// std::invalid_argument naming a key a --set item set ("cameras.front.rate_hz = 1e+12 exceeds
// sitl.dynamics_rate_hz") becomes a config::UsageError (exit 2) starting with that item; other
// errors pass unchanged.
void CheckAssembled(const config::ConfigTree& tree, const std::function<void()>& check);

// The effective configuration: built-in `defaults_yaml` < --config files < --set items.
config::ConfigTree LoadConfig(const CommonOptions& options, const std::string& defaults_yaml);

}  // namespace aperture::apps
