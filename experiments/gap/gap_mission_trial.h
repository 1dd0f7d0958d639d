#pragma once
// The vision gap mission (planning/gap_mission/gap_mission.h, built by MakeGapMission) as a
// GapTrialAutopilot for `aperture bench gap`: camera images + IMU only; the bench reads its
// traverse plan, traverse start time, filter estimate and gap estimate (mission frame).
#include "experiments/gap/gap_trial_autopilot.h"
#include "planning/gap_mission/gap_mission.h"

namespace aperture::experiments {

// Each trial's mission flies GapTrialSetup::mission: the scenario's camera, pattern sizes and
// nominal IMU noise specification (GapMissionParamsFor) with the bench's `mission` section.
GapTrialAutopilotFactory MakeGapMissionTrialFactory();

}  // namespace aperture::experiments
