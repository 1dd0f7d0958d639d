#pragma once
// Test support: a figure in scientific notation with 3 significant digits ("1.23e-04"), for the
// measured errors the tests print next to their bounds.
#include <iomanip>
#include <sstream>
#include <string>

namespace aperture::test_support {

inline std::string Sci(double value) {
  std::ostringstream os;
  os << std::scientific << std::setprecision(2) << value;
  return os.str();
}

}  // namespace aperture::test_support
