// The paper's vehicle preset: seed 000's mass and dimensions, ours scaled for the rest, and the
// ground-truth gap flight still passes with it.
#include "experiments/gap/paper_gap_vehicle.h"

#include <gtest/gtest.h>

#include "experiments/gap/gap_bench.h"
#include "experiments/gap/gap_footprint.h"
#include "experiments/gap/ground_truth_gap_autopilot.h"

namespace aperture::experiments {
namespace {

TEST(PaperGapVehicle, HasThePapersMassAndDimensionsAndOurHoverCommand) {
  sim::ScenarioParams params;
  UsePaperGapVehicle(&params);
  ASSERT_TRUE(params.dynamics && params.collision);
  const control::VehicleParameters& paper = params.dynamics->vehicle;
  const control::VehicleParameters ours;
  EXPECT_DOUBLE_EQ(paper.mass_kg, 0.83);
  const VehicleFootprint footprint = VehicleFootprintOf(paper, *params.collision);
  // Largest length between propeller tips: across the diagonal, 2 (arm + propeller radius).
  EXPECT_NEAR(2.0 * (footprint.rotor_p_B[0].norm() + footprint.propeller_radius_m), 0.55, 1e-12);
  EXPECT_NEAR(2.0 * footprint.body_radius_m, 0.12, 1e-12);
  // Scaled by the mass: each rotor hovers at the same command, with the same thrust-to-weight.
  const auto hover_command = [](const control::VehicleParameters& v) {
    return v.rotor.CommandFromThrust(v.mass_kg * v.gravity_mps2 / 4.0);
  };
  EXPECT_NEAR(hover_command(paper), hover_command(ours), 1e-9);
  EXPECT_NEAR(paper.rotor.MaxThrust() / paper.mass_kg, ours.rotor.MaxThrust() / ours.mass_kg, 1e-9);
  sim::CollisionChecker::Validate(*params.dynamics, *params.collision);
}

TEST(PaperGapVehicle, TheBenchFliesItThroughTheGap) {
  GapBenchOptions options;
  options.trials = 1;
  options.seed = 11;
  options.duration_s = 6.0;
  options.render_cameras = false;
  options.paper_configuration = false;
  options.vehicle.mismatch = false;
  options.paper_vehicle = true;
  const GapBenchSetup setup = PrepareGapBench(options);
  ASSERT_TRUE(setup.base.dynamics.has_value());
  EXPECT_DOUBLE_EQ(setup.base.dynamics->vehicle.mass_kg, 0.83);
  EXPECT_DOUBLE_EQ(setup.scenario_config["collision"]["body_radius_m"].get<double>(), 0.06);
  const GapBenchResult result = RunGapBench(options, setup, MakeGroundTruthGapAutopilotFactory());
  ASSERT_EQ(result.trials.size(), 1u);
  EXPECT_TRUE(result.trials[0].evaluation.success) << result.trials[0].evaluation.failure_reason;
}

}  // namespace
}  // namespace aperture::experiments
