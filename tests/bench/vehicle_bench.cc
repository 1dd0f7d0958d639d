// Throughput of the simulated vehicle: RK4 steps of QuadrotorDynamics per second (report only).
#include <benchmark/benchmark.h>

#include "sim/sensors/imu_sensor.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {
namespace {

control::QuadState InitialState() {
  control::QuadState initial;
  initial.v_W = Eigen::Vector3d(2.0, -1.0, 0.5);
  initial.omega_B = Eigen::Vector3d(0.5, -0.3, 0.2);
  return initial;
}

// The constant torque spins the vehicle up without bound; restarting it (clock running on, as the
// IMU needs) keeps the numbers in a realistic range (the cost of a step does not depend on them).
void RestartWhenSpunUp(QuadrotorDynamics* vehicle) {
  if (vehicle->state().omega_B.norm() < 30.0) return;
  control::QuadState restart = InitialState();
  restart.t_s = vehicle->state().t_s;
  vehicle->SetState(restart);
}

QuadrotorDynamics MakeManoeuvringVehicle() {
  QuadrotorDynamicsParams params;
  params.vehicle.thrust_velocity_coeff_kh = 0.01;
  QuadrotorDynamics vehicle(params, InitialState());
  vehicle.SetMotorCommands(Eigen::Vector4d(0.2, 0.0, 0.15, 0.05));  // rotors lagging, torques on
  return vehicle;
}

void BM_DynamicsStep1ms(benchmark::State& state) {
  QuadrotorDynamics vehicle = MakeManoeuvringVehicle();
  for (auto _ : state) {
    vehicle.Step(0.001);
    RestartWhenSpunUp(&vehicle);
    benchmark::DoNotOptimize(vehicle.state());
  }
  state.SetItemsProcessed(state.iterations());  // items/s = steps/s
}
BENCHMARK(BM_DynamicsStep1ms);

void BM_DynamicsStepWithImu(benchmark::State& state) {
  QuadrotorDynamics vehicle = MakeManoeuvringVehicle();
  ImuSensor imu{ImuSensorParams()};
  for (auto _ : state) {
    vehicle.Step(0.001);
    RestartWhenSpunUp(&vehicle);
    auto samples = imu.Update(vehicle.state().t_s, vehicle.SpecificForce_B(), vehicle.state().omega_B);
    benchmark::DoNotOptimize(samples);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DynamicsStepWithImu);

}  // namespace
}  // namespace aperture::sim
