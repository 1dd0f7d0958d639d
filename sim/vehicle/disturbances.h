#pragma once
// Time-scripted disturbances for the simulated quadrotor: wind (steady plus boxcar gusts, entering
// the rotor-drag terms of (F.2), (F.4), (F.5) as airspeed v_W - v_wind_W), impulsive pushes
// (instantaneous changes of linear and angular momentum) and a constant body torque. Times are on the simulator clock [s].
#include <vector>

#include <Eigen/Core>

#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

// Wind velocity added to the steady wind while t_start_s <= t < t_start_s + duration_s.
struct WindGust {
  double t_start_s = 0.0;
  double duration_s = 0.0;                                  // > 0
  Eigen::Vector3d wind_W_mps = Eigen::Vector3d::Zero();
};

// Impulse applied at t_s: v_W += impulse_W_Ns / m, omega_B += J^-1 angular_impulse_B_Nms.
struct Push {
  double t_s = 0.0;
  Eigen::Vector3d impulse_W_Ns = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_impulse_B_Nms = Eigen::Vector3d::Zero();  // optional, zero = none
};

struct DisturbanceParams {
  Eigen::Vector3d steady_wind_W_mps = Eigen::Vector3d::Zero();  // default: calm air
  std::vector<WindGust> gusts;                                  // may overlap: they add up
  std::vector<Push> pushes;                                     // any order
  // Constant external torque in B [N m], e.g. gravity acting on a centre of mass offset r_B from
  // the rotor centre of a hovering vehicle (m g z_W x r_B ~ r_B x (-m g z_B)): a real vehicle
  // needs unequal rotor thrusts to hover. Zero by default.
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();

  // Throws std::invalid_argument naming the entry (e.g. "gusts[2].duration_s") for non-finite
  // values, negative times or non-positive gust durations.
  void Validate() const;
};

class Disturbances {
 public:
  explicit Disturbances(const DisturbanceParams& params);

  // Steady wind plus every gust active at t_s [m/s].
  Eigen::Vector3d WindVelocity_W(double t_s) const;

  // Advances `vehicle` by dt_s from its current time, splitting the step at gust edges and push
  // times so the wind is exact (piecewise constant) and each push lands at its own time. Pushes
  // scheduled before the vehicle's current time and not yet applied are applied at once.
  // Overwrites the vehicle's wind and external-torque inputs. Throws std::invalid_argument if dt_s <= 0.
  void StepVehicle(double dt_s, QuadrotorDynamics* vehicle);

  int pushes_applied() const { return next_push_; }

 private:
  DisturbanceParams params_;  // pushes sorted by time
  std::vector<double> event_times_s_;  // sorted gust edges and push times
  int next_push_ = 0;
};

}  // namespace aperture::sim
