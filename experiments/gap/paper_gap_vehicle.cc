#include "experiments/gap/paper_gap_vehicle.h"

namespace aperture::experiments {

void UsePaperGapVehicle(sim::ScenarioParams* params) {
  sim::QuadrotorDynamicsParams dynamics = params->dynamics.value_or(sim::QuadrotorDynamicsParams{});
  control::VehicleParameters& vehicle = dynamics.vehicle;
  const double scale = kPaperVehicleMassKg / vehicle.mass_kg;
  vehicle.mass_kg = kPaperVehicleMassKg;
  vehicle.inertia_diag_kgm2 *= scale;
  vehicle.rotor.thrust_coeffs_N *= scale;
  vehicle.rotor.torque_coeffs_Nm *= scale;
  sim::CollisionParams collision = params->collision.value_or(sim::CollisionParams{});
  collision.body_radius_m = 0.5 * kPaperVehicleHeightM;
  collision.propeller_radius_m = 0.5 * kPaperVehicleTipToTipM - vehicle.arm_length_m;
  params->dynamics = dynamics;
  params->collision = collision;
}

}  // namespace aperture::experiments
