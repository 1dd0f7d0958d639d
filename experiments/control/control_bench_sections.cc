#include "experiments/control/control_bench_sections.h"

#include <stdexcept>

#include "config/usage_error.h"
#include "experiments/control/drag_sections.h"
#include "experiments/control/low_level_sections.h"
#include "experiments/control/recovery_section.h"

namespace aperture::experiments {

std::vector<ControlBenchSection> ControlBenchSections() {
  return {
      MakeDragSection(),       MakeBodyRateSection(), MakeMixerSection(),
      MakeSaturationSection(), MakeRecoverySection(),
  };
}

std::vector<ControlBenchSection> SelectControlBenchSections(const std::vector<std::string>& only) {
  std::vector<ControlBenchSection> all = ControlBenchSections();
  if (only.empty()) return all;
  std::vector<ControlBenchSection> selected;
  std::string known;
  for (const auto& section : all) known += (known.empty() ? "" : ", ") + section.key;
  for (const std::string& key : only) {
    bool found = false;
    for (const auto& section : all) {
      if (section.key == key) {
        selected.push_back(section);
        found = true;
      }
    }
    if (!found) {
      throw config::UsageError("--only: unknown section '" + key + "'; known: " + known);
    }
  }
  return selected;
}

}  // namespace aperture::experiments
