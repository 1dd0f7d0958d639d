#include "perception/gap/gap_pattern.h"

#include "control/require.h"

namespace aperture::perception {

void GapPattern::ValidatePattern(const std::string& owner) const {
  for (int i = 0; i < 2; ++i) {
    const std::string axis = i == 0 ? ".x" : ".y";
    control::RequirePositive(opening_size_m[i], owner + ".opening_size_m" + axis);
    control::Require(inner_size_m[i] > opening_size_m[i], owner + ".inner_size_m" + axis,
                     inner_size_m[i], "must exceed opening_size_m");
    control::Require(outer_size_m[i] > inner_size_m[i], owner + ".outer_size_m" + axis,
                     outer_size_m[i], "must exceed inner_size_m");
  }
  control::Require(opening_size_m.x() > opening_size_m.y(), owner + ".opening_size_m.x",
                   opening_size_m.x(), "must be the long side (x > y)");
}

}  // namespace aperture::perception
