#pragma once
// How a fault-sweep flight ended (issue 18 item 5): success (the mission's own evaluation
// passed), safe abort (it did not, but the vehicle ended without collision in a stable state --
// hovering, or resting on its landing gear), or crash (a collision, or still moving, tilted or
// tumbling when the run ended: a vehicle that lost its estimate and drifts away counts here).
//
//   FlightOutcome outcome = ClassifyFlight(run.evaluation.passed, sitl_result);
#include <string>

#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

// The stable end state: every ground-truth state of the run's last window_s within these bounds.
// Looser than a mission's own hover check: a safe abort need not be precise, only under control.
struct SafeStateCriteria {
  double window_s = 0.5;        // [s]
  double max_speed_mps = 0.5;   // |v_W|
  double max_tilt_deg = 20.0;   // angle between z_B and z_W
  double max_rate_radps = 1.0;  // |omega_xy| (turning about z_B is allowed)
};

enum class FlightOutcomeKind { kSuccess, kSafeAbort, kCrash };
const char* ToString(FlightOutcomeKind kind);  // "success", "safe_abort", "crash"

struct FlightOutcome {
  FlightOutcomeKind kind = FlightOutcomeKind::kCrash;
  std::string reason;  // empty on success; else the collision or the unsafe end state
};

// A run shorter than the window, or with an empty trajectory, is a crash (it did not end
// stable). Throws std::invalid_argument for non-positive criteria.
FlightOutcome ClassifyFlight(bool mission_passed, const sim::SitlResult& result,
                             const SafeStateCriteria& criteria = {});

}  // namespace aperture::experiments
