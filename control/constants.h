#pragma once
// Numeric and physical constants shared by every layer (control is the lowest layer that needs
// them), one definition each instead of a copy per file: angles in rad unless the name says deg.
#include <limits>

namespace aperture::control {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;  // rad per deg
inline constexpr double kRadToDeg = 180.0 / kPi;  // deg per rad
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
// The gravity of the vehicle model's defaults (VehicleParameters, the filters' gravity_mps2).
inline constexpr double kGravity_mps2 = 9.81;

}  // namespace aperture::control
