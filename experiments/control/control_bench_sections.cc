#include "experiments/control/control_bench_sections.h"

#include "experiments/control/drag_sections.h"
#include "experiments/control/low_level_sections.h"
#include "experiments/control/recovery_section.h"

namespace aperture::experiments {

std::vector<ControlBenchSection> ControlBenchSections() {
  return {
      MakeDragSection(),
      MakeDragIdSection(),
      MakeBodyRateSection(),
      MakeMixerSection(),
      MakeSaturationSection(),
      MakeRecoverySection(),
  };
}

}  // namespace aperture::experiments
