#pragma once
// Every section of `aperture bench control`, in the order they run (issue 4). A new comparison
// adds its Make<Name>Section() to the list in control_bench_sections.cc.
#include <string>
#include <vector>

#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

std::vector<ControlBenchSection> ControlBenchSections();

// The sections named by `only` (in that order), or all of them when it is empty.
// std::invalid_argument naming an unknown key and listing the known ones.
std::vector<ControlBenchSection> SelectControlBenchSections(const std::vector<std::string>& only);

}  // namespace aperture::experiments
