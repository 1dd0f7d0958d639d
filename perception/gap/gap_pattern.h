#pragma once
// Geometry of the patterned gap of Falanga et al. 2017 (seed 000), Sec. III-A: what the detector
// looks for (perception/gap/gap_detector.h) and what the simulator draws
// (sim/scene/gap_pattern_object.h), with no detector tuning in it. All rectangles concentric,
// sides parallel, on one plane:
//   white surround | black band | white band | opening (the gap, seen through)
//                  ^ outer_size_m            ^ opening_size_m
//                               ^ inner_size_m
// Sizes are (x, y) [m] in the gap frame G (x_G along the long side); see gap_detector.h for G.
#include <Eigen/Core>
#include <string>

namespace aperture::perception {

struct GapPattern {
  // The seed's gap is 0.8 x 0.28 m; the margins are the `gap` scenario's pattern: 5 cm white band,
  // 20 cm black band, so the white band is >= 2 px wide on a 180 deg fisheye at 5 m.
  Eigen::Vector2d opening_size_m = Eigen::Vector2d(0.8, 0.28);
  Eigen::Vector2d inner_size_m = Eigen::Vector2d(0.9, 0.38);
  Eigen::Vector2d outer_size_m = Eigen::Vector2d(1.3, 0.78);

  // Throws std::invalid_argument naming "<owner>.<field>.<axis>" unless opening < inner < outer in
  // both directions, every size > 0 and x is the long side of the opening.
  void ValidatePattern(const std::string& owner) const;
};

}  // namespace aperture::perception
