#include "experiments/control/drag_sections.h"

#include <cmath>
#include <memory>
#include <nlopt.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/svg_plot.h"
#include "sim/sitl/tracking_flight.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::experiments {
namespace {

constexpr double kRampS = 3.0;  // smooth speed ramp in and out (SpeedRampParams default)

std::shared_ptr<const control::ReferenceTrajectory> MakeReference(const std::string& name,
                                                                  double loops) {
  control::SpeedRampParams ramp;
  ramp.ramp_s = kRampS;
  ramp.num_loops = loops;
  if (name == "circle") {
    control::CircleTrajectoryParams params;
    params.ramp = ramp;
    return std::make_shared<control::CircleTrajectory>(params);
  }
  control::LemniscateTrajectoryParams params;
  params.ramp = ramp;
  return std::make_shared<control::LemniscateTrajectory>(params);
}

// A flight of `reference` with E_a measured over its full-speed loops (between the ramps).
sim::TrackingFlightParams FullSpeedFlight(std::shared_ptr<const control::ReferenceTrajectory> ref,
                                          const ControlBenchOptions& options) {
  sim::TrackingFlightParams params = BenchTrackingFlight(options);
  params.error_begin_s = kRampS;
  params.error_end_s = ref->EndTimeS() - kRampS;
  params.reference = std::move(ref);
  return params;
}

// Figs. F.6, F.7: the F.7 speed ramp (maximum speed 0 -> 5 m/s linearly in 30 s), error over the
// reference speed without and with compensation; keys ramp_E_a_off, ramp_E_a_on over the ramp.
void RunSpeedRamp(const std::string& name, const ControlBenchOptions& options, nlohmann::json* out,
                  output::HtmlReport* report) {
  constexpr double kRampEndS = 30.0;
  std::shared_ptr<const control::ReferenceTrajectory> reference;
  if (name == "circle") {
    reference = std::make_shared<control::CircleTrajectory>(
        control::CircleTrajectoryParams::ThesisSpeedRamp());
  } else {
    reference = std::make_shared<control::LemniscateTrajectory>(
        control::LemniscateTrajectoryParams::ThesisSpeedRamp());
  }
  output::SvgPlot plot({name + ": error over speed on the 0 -> 5 m/s ramp (Figs. F.6, F.7 analog)",
                        "reference speed [m/s]", "|p - p_ref| [m]"});
  for (const bool compensate : {false, true}) {
    sim::TrackingFlightParams params = BenchTrackingFlight(options);
    params.reference = reference;
    params.duration_s = kRampEndS;
    params.control.position.compensate_rotor_drag = compensate;
    const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);
    const std::string tag = compensate ? "on" : "off";
    (*out)["ramp_E_a_" + tag] = flight.error.E_a_m;
    std::vector<double> speed, error;
    for (size_t k = 0; k < flight.sitl.trajectory.size(); ++k) {
      speed.push_back(flight.reference[k].v_W.norm());
      error.push_back((flight.sitl.trajectory[k].p_WB - flight.reference[k].p_W).norm());
    }
    plot.AddLine("drag compensation " + tag, speed, error);
  }
  report->AddSvg(plot.Render());
}

void RunDrag(const ControlBenchOptions& options, nlohmann::json* summary,
             output::HtmlReport* report) {
  report->AddSection("Rotor-drag compensation (thesis F.7.4, Table F.1)");
  report->AddParagraph(
      "Circle (r 1.8 m, 4 m/s) and Gerono lemniscate (max 4 m/s) flown on ground truth without "
      "and with rotor-drag compensation of the controllers' model (d_x = 0.5, d_y = 0.35 1/s) on "
      "the bench vehicle (see 'Simulated vehicle'), IMU noise. E_a (F.39) over the full-speed "
      "loops.");
  const double loops = options.quick ? 1.0 : 10.0;  // Table F.1: ten loops
  for (const std::string name : {"circle", "lemniscate"}) {
    const auto reference = MakeReference(name, loops);
    nlohmann::json& out = (*summary)["drag"][name];
    output::SvgPlot paths({name + ": x-y path (Figs. F.4, F.5 analog)", "x [m]", "y [m]"});
    output::SvgPlot errors(
        {name + ": position error (Figs. F.6, F.7 analog)", "t [s]", "|p - p_ref| [m]"});
    double E_a_off = 0.0;
    for (const bool compensate : {false, true}) {
      sim::TrackingFlightParams params = FullSpeedFlight(reference, options);
      params.control.position.compensate_rotor_drag = compensate;
      const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);
      const std::string tag = compensate ? "on" : "off";
      out["E_a_" + tag] = flight.error.E_a_m;
      out["max_" + tag] = flight.error.max_m;
      if (compensate) {
        out["reduction"] = 1.0 - flight.error.E_a_m / E_a_off;
      } else {
        E_a_off = flight.error.E_a_m;
      }
      std::vector<double> t, x, y, e, x_ref, y_ref;
      for (size_t k = 0; k < flight.sitl.trajectory.size(); ++k) {
        const control::QuadState& s = flight.sitl.trajectory[k];
        t.push_back(s.t_s);
        x.push_back(s.p_WB.x());
        y.push_back(s.p_WB.y());
        x_ref.push_back(flight.reference[k].p_W.x());
        y_ref.push_back(flight.reference[k].p_W.y());
        e.push_back((s.p_WB - flight.reference[k].p_W).norm());
      }
      if (!compensate) paths.AddLine("reference", x_ref, y_ref);
      paths.AddLine("drag compensation " + tag, x, y);
      errors.AddLine("drag compensation " + tag, t, e);
    }
    report->AddSvg(paths.Render());
    report->AddSvg(errors.Render());
    if (!options.quick) RunSpeedRamp(name, options, &out, report);
  }
  report->AddTable((*summary)["drag"], "drag: E_a and max error [m], reduction = 1 - on/off");
}

struct DragIdProblem {
  sim::TrackingFlightParams flight;
  int evaluations = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  std::vector<double> evaluation, best_dx, best_dy, best_E_a;
};

// NLopt objective, x = [d_x, d_y] of the controller's model [1/s].
double DragIdCost(const std::vector<double>& x, std::vector<double>& /*gradient*/, void* data) {
  auto* problem = static_cast<DragIdProblem*>(data);
  sim::TrackingFlightParams params = problem->flight;
  control::VehicleParameters model = params.dynamics.vehicle;
  model.rotor_drag_D_per_s.x() = x[0];
  model.rotor_drag_D_per_s.y() = x[1];
  params.controller_model = model;
  const double cost = sim::FlyTrackingFlight(params).error.E_a_m;
  ++problem->evaluations;
  if (cost < problem->best_cost) {
    problem->best_cost = cost;
    problem->best = Eigen::Vector2d(x[0], x[1]);
  }
  problem->evaluation.push_back(problem->evaluations);
  problem->best_dx.push_back(problem->best.x());
  problem->best_dy.push_back(problem->best.y());
  problem->best_E_a.push_back(problem->best_cost);
  return cost;
}

void RunDragId(const ControlBenchOptions& options, nlohmann::json* summary,
               output::HtmlReport* report) {
  // F.7.3: two loops of the trajectory per evaluation, d_z = k_h = 0 (the bench vehicle's).
  DragIdProblem problem;
  problem.flight = FullSpeedFlight(MakeReference("circle", options.quick ? 1.0 : 2.0), options);
  // The simulated vehicle's D (with vehicle.mismatch its value in hover: its rotor drag grows
  // with thrust and a quadratic parasitic drag adds to it, so no D describes it exactly).
  Eigen::Vector3d true_D = problem.flight.dynamics.vehicle.rotor_drag_D_per_s;
  if (options.vehicle.mismatch) {
    true_D = sim::MismatchedVehicle(
                 problem.flight.dynamics.vehicle,
                 sim::DrawVehicleMismatch(options.vehicle.mismatch_bounds, problem.flight.seed))
                 .rotor_drag_D_per_s;
  }

  nlopt::opt optimizer(nlopt::LN_NELDERMEAD, 2);
  optimizer.set_min_objective(DragIdCost, &problem);
  optimizer.set_lower_bounds({0.0, 0.0});
  optimizer.set_upper_bounds({2.0, 2.0});
  optimizer.set_initial_step({0.3, 0.3});
  // 5e-3 1/s is 1-1.5 % of the coefficients; the thesis converged after ~70 flights.
  optimizer.set_xtol_abs(options.quick ? 0.01 : 5e-3);
  optimizer.set_maxeval(options.quick ? 20 : 80);
  std::vector<double> x = {0.0, 0.0};  // start from the drag-free model
  double cost = 0.0;
  std::string status;
  try {
    switch (optimizer.optimize(x, cost)) {
      case nlopt::XTOL_REACHED:
        status = "xtol_reached";
        break;
      case nlopt::FTOL_REACHED:
        status = "ftol_reached";
        break;
      case nlopt::MAXEVAL_REACHED:
        status = "maxeval_reached";
        break;
      default:
        status = "success";
        break;
    }
  } catch (const nlopt::roundoff_limited&) {
    status = "roundoff_limited";
  }
  nlohmann::json& out = (*summary)["drag_id"];
  out["true"] = {{"dx", true_D.x()}, {"dy", true_D.y()}};
  out["estimated"] = {{"dx", problem.best.x()}, {"dy", problem.best.y()}};
  out["relative_error"] = {{"dx", problem.best.x() / true_D.x() - 1.0},
                           {"dy", problem.best.y() / true_D.y() - 1.0}};
  out["evaluations"] = problem.evaluations;
  out["E_a_at_estimate"] = problem.best_cost;
  out["nlopt_result"] = status;

  report->AddSection("Rotor-drag identification (thesis F.6, F.7.3)");
  report->AddParagraph(
      "Nelder-Mead (NLopt LN_NELDERMEAD) over the controller's d_x, d_y, each evaluation one SITL "
      "flight of the circle (" +
      std::string(options.quick ? "one loop" : "two loops") +
      " at 4 m/s) with cost E_a (F.39), starting from the drag-free model.");
  report->AddSvg(
      output::SvgPlot(
          {"Best drag coefficients per evaluation (Fig. F.3 analog)", "evaluation", "d [1/s]"})
          .AddLine("d_x", problem.evaluation, problem.best_dx)
          .AddLine("d_y", problem.evaluation, problem.best_dy)
          .AddLine("true d_x", {1.0, double(problem.evaluations)}, {true_D.x(), true_D.x()})
          .AddLine("true d_y", {1.0, double(problem.evaluations)}, {true_D.y(), true_D.y()})
          .Render());
  report->AddSvg(output::SvgPlot({"Best E_a per evaluation", "evaluation", "E_a [m]"})
                     .AddLine("E_a", problem.evaluation, problem.best_E_a)
                     .Render());
  report->AddTable(out, "drag_id [1/s]");
}

}  // namespace

ControlBenchSection MakeDragSection() { return {"drag", RunDrag}; }
ControlBenchSection MakeDragIdSection() { return {"drag_id", RunDragId}; }

}  // namespace aperture::experiments
