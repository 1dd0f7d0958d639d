#pragma once
// GapTrialRecord (gap_bench.h) as JSON: the per-trial entry of summary.json, and the complete
// record that shards of `aperture bench gap --shard K/N` store for the merge
// (experiments/bench/monte_carlo_bench.h). The complete record is the summary entry plus
// the traces, the crossing's state, the autopilot's name and the blur subframes:
// GapTrialRecordFromJson(GapTrialRecordToJson(r)) equals r bit for bit in every field the bench's
// writers read (all but `plan`, which only the evaluation during the flight uses). Non-finite
// values stay exact in memory and in CBOR (JSON text would turn them into null).
#include <nlohmann/json.hpp>

#include "experiments/gap/gap_bench.h"

namespace aperture::experiments {

// A GapStateError as {position_m, velocity_mps, orientation_deg, time_s} and back (a null time_s,
// NaN in JSON text, reads as NaN); std::out_of_range/nlohmann errors for a missing key.
nlohmann::json GapStateErrorToJson(const GapStateError& error);
GapStateError GapStateErrorFromJson(const nlohmann::json& json);

// summary.json "per_trial" entry: the trial's draws, outcome, crossing and error at the gap.
nlohmann::json GapTrialSummaryJson(const GapTrialRecord& record);

nlohmann::json GapTrialRecordToJson(const GapTrialRecord& record);
// std::invalid_argument naming the missing or malformed key.
GapTrialRecord GapTrialRecordFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
