#include "apps/command_support.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "config/usage_error.h"
#include "config/yaml_write_archive.h"
#include "perception/graph/front_end_registry.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_params.h"

namespace aperture::apps {
namespace {

// The seed check: decimal digits only (CLI11 would turn "-1" into 2^64 - 1), at most 2^64 - 1.
std::string SeedError(const std::string& text) {
  const std::string rule =
      "a seed is an integer from 0 to 18446744073709551615 written in decimal digits";
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return "'" + text + "' is not a seed: " + rule;
  }
  errno = 0;
  std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return "'" + text + "' is too large: " + rule;
  return "";
}

std::string Readable(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

}  // namespace

void AddCommonOptions(CLI::App* command, CommonOptions* options) {
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command
      ->add_option("--config", options->config_files,
                   "YAML parameter file (repeatable; later files win)")
      ->check(CLI::ExistingFile);
  command->add_option("--set", options->set_items,
                      "Parameter override key=value, e.g. image_quality.histogram_bins=32 "
                      "(repeatable; wins over --config)");
}

void AddOverwriteFlag(CLI::App* command, bool* overwrite) {
  command->add_flag("--overwrite", *overwrite,
                    "Reuse an --out folder that holds an earlier run's outputs: remove the files "
                    "that run created first (without it such a folder is refused)");
}

output::OutputFolder OpenOutputFolder(const std::string& out_dir, bool overwrite) {
  try {
    return output::OutputFolder(out_dir, overwrite);
  } catch (const output::FolderInUseError& e) {
    throw config::UsageError(e.what());
  }
}

CLI::Validator SeedValidator() { return CLI::Validator(SeedError, "UINT64", "seed"); }

CLI::Option* AddSeedOption(CLI::App* command, std::uint64_t* seed, const std::string& description) {
  return command->add_option("--seed", *seed, description)->check(SeedValidator());
}

CLI::Option* AddSeedOption(CLI::App* command, std::optional<std::uint64_t>* seed,
                           const std::string& description) {
  return command->add_option("--seed", *seed, description)->check(SeedValidator());
}

CLI::Validator FiniteNumberIn(double min, double max, bool min_inclusive) {
  const std::string range =
      (min_inclusive ? "[" : "(") + Readable(min) + ", " + Readable(max) + "]";
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) {
          return "'" + text + "' is not a number";
        }
        const bool above_min = min_inclusive ? value >= min : value > min;
        if (!std::isfinite(value) || !above_min || !(value <= max)) {
          return "'" + text + "' is not a finite number in " + range;
        }
        return "";
      },
      "NUMBER in " + range, "finite number");
}

CLI::Validator IntegerIn(long long min, long long max) {
  const std::string range = max == std::numeric_limits<int>::max()
                                ? ">= " + std::to_string(min)
                                : "in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        const std::size_t digits = !text.empty() && text[0] == '-' ? 1 : 0;
        errno = 0;
        const long long value = std::strtoll(text.c_str(), nullptr, 10);
        if (text.size() == digits ||
            text.find_first_not_of("0123456789", digits) != std::string::npos || errno == ERANGE ||
            value < min || value > max) {
          return "'" + text + "' is not an integer " + range;
        }
        return "";
      },
      "INT " + range, "integer");
}

CLI::Validator CommaListOf(const std::vector<std::string>& allowed) {
  std::string names;
  for (const std::string& name : allowed) names += (names.empty() ? "" : ", ") + name;
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        for (const std::string& item : perception::SplitFrontEndList(text)) {
          if (std::find(allowed.begin(), allowed.end(), item) == allowed.end()) {
            return "'" + item + "' is not one of: " + names;
          }
        }
        return "";
      },
      "LIST of " + names, "comma list");
}

std::string BuiltinScenarioList() {
  std::string names;
  for (const std::string& name : sim::BuiltinScenarioNames())
    names += (names.empty() ? "" : ", ") + name;
  return names;
}

void RequireBuiltinScenario(const std::string& name) {
  if (name.empty()) {
    throw config::UsageError("a scenario NAME is required: one of " + BuiltinScenarioList());
  }
  try {
    sim::BuiltinScenarioYaml(name);
  } catch (const std::invalid_argument& e) {
    throw config::UsageError(e.what());
  }
}

void PutEffectiveLeds(const sim::ScenarioParams& params, config::ConfigTree* tree) {
  if (params.scenario != "led") return;
  YAML::Node led = YAML::Clone(tree->root()["led"]);
  if (!led.IsMap()) led = YAML::Node(YAML::NodeType::Map);
  led["leds"] = config::YamlWriteArchive::Encode(params.led.leds_B);
  tree->Put("led", led, "effective configuration");
}

void CheckAssembled(const config::ConfigTree& tree, const std::function<void()>& check) {
  try {
    check();
  } catch (const config::UsageError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    const std::string item = tree.SetItemNamedIn(e.what());
    if (item.empty()) throw;
    throw config::UsageError(item + ": " + e.what());
  }
}

config::ConfigTree LoadConfig(const CommonOptions& options, const std::string& defaults_yaml) {
  return config::ConfigTree::FromCommandLine(defaults_yaml, options.config_files,
                                             options.set_items);
}

}  // namespace aperture::apps
