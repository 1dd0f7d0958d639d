#pragma once
// Every section of `aperture bench control`, in the order they run (issue 4). A new comparison
// adds its Make<Name>Section() to the list in control_bench_sections.cc.
#include <vector>

#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

std::vector<ControlBenchSection> ControlBenchSections();

}  // namespace aperture::experiments
