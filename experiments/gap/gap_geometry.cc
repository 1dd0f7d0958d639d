#include "experiments/gap/gap_geometry.h"

namespace aperture::experiments {

GapGeometry GapGeometryOf(const sim::Scenario& scenario) {
  GapGeometry gap;
  gap.T_WG = scenario.scene().object("gap").T_WO;
  gap.opening_m = scenario.params().gap.opening_m;
  gap.panel_m = scenario.params().gap.panel_m;
  return gap;
}

}  // namespace aperture::experiments
