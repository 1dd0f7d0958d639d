#pragma once
// Registers every front end of the perception library with `registry` (explicit registration:
// see front_end_registry.h). Add a line to RegisterBuiltinFrontEnds for each new front end.
#include "perception/graph/front_end_registry.h"

namespace aperture::perception {

void RegisterBuiltinFrontEnds(FrontEndRegistry& registry);

}  // namespace aperture::perception
