#pragma once
// Text form of numbers for CSV/TUM/SVG output.
#include <string>

namespace aperture::output {

// Shortest of %.15g/%.17g that reads back to exactly `value` (so files round-trip bit-exactly
// without printing 0.1 as 0.10000000000000001). Non-finite values print as "nan", "inf", "-inf",
// which numpy, pandas and std::strtod read back.
std::string FormatDouble(double value);

}  // namespace aperture::output
