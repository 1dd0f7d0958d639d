#include "experiments/control/control_bench_sections.h"

#include "experiments/control/drag_sections.h"

namespace aperture::experiments {

std::vector<ControlBenchSection> ControlBenchSections() {
  return {
      MakeDragSection(),
      MakeDragIdSection(),
  };
}

}  // namespace aperture::experiments
