#pragma once
// The outcome line of a bench whose summary carries an `acceptance` map of named checks (true =
// met): "passed" when every check is met, else "failed", with one figure per check.
#include <nlohmann/json.hpp>

#include "output/html_report.h"

namespace aperture::output {

ReportOutcome AcceptanceOutcome(const nlohmann::json& acceptance);

}  // namespace aperture::output
