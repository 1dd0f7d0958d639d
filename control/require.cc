#include "control/require.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace aperture::control {
namespace {

std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

void Require(bool ok, const std::string& name, double value, const std::string& rule) {
  if (!ok) throw std::invalid_argument(name + " = " + Format(value) + " " + rule);
}

void Require(bool ok, const std::string& name, const std::string& rule) {
  if (!ok) throw std::invalid_argument(name + " " + rule);
}

void RequireFinite(double value, const std::string& name) {
  Require(std::isfinite(value), name, value, "must be finite");
}

void RequirePositive(double value, const std::string& name) {
  Require(std::isfinite(value) && value > 0.0, name, value, "must be finite and > 0");
}

void RequireNonNegative(double value, const std::string& name) {
  Require(std::isfinite(value) && value >= 0.0, name, value, "must be finite and >= 0");
}

void RequireAtLeast(double value, double minimum, const std::string& name) {
  Require(value >= minimum, name, value, "must be >= " + Format(minimum));
}

void RequireInRange(double value, double minimum, double maximum, const std::string& name) {
  Require(std::isfinite(value) && value >= minimum && value <= maximum, name, value,
          "must be in [" + Format(minimum) + ", " + Format(maximum) + "]");
}

}  // namespace aperture::control
