#include "output/acceptance_outcome.h"

#include <string>

namespace aperture::output {

ReportOutcome AcceptanceOutcome(const nlohmann::json& acceptance) {
  ReportOutcome outcome{"passed", "", {}};
  int met = 0;
  for (const auto& [check, value] : acceptance.items()) {
    const bool ok = value.is_boolean() && value.get<bool>();
    met += ok;
    if (!ok) outcome.verdict = "failed";
    outcome.figures.push_back({check, ok ? "met" : "NOT met", "met"});
  }
  outcome.headline =
      std::to_string(met) + " of " + std::to_string(acceptance.size()) + " acceptance checks met.";
  return outcome;
}

}  // namespace aperture::output
