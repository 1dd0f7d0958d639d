#include "experiments/control/drag_sections.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
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

// `params` flown with the controllers' model carrying rotor-drag coefficients D_xy (d_z = 0,
// k_h = 0 as in F.7.3) and compensating them (F.7.4).
sim::TrackingFlightParams WithControllerDrag(sim::TrackingFlightParams params,
                                             const Eigen::Vector2d& D_xy_per_s) {
  control::VehicleParameters model = params.dynamics.vehicle;
  model.rotor_drag_D_per_s.x() = D_xy_per_s.x();
  model.rotor_drag_D_per_s.y() = D_xy_per_s.y();
  params.controller_model = model;
  params.control.position.compensate_rotor_drag = true;
  return params;
}

// The simulated vehicle's D (with vehicle.mismatch its value in hover: its rotor drag grows with
// thrust and a quadratic parasitic drag adds to it, so no D describes it exactly).
Eigen::Vector3d SimulatedVehicleD(const sim::TrackingFlightParams& flight,
                                  const ControlBenchOptions& options) {
  if (!options.vehicle.mismatch) return flight.dynamics.vehicle.rotor_drag_D_per_s;
  return sim::MismatchedVehicle(
             flight.dynamics.vehicle,
             sim::DrawVehicleMismatch(options.vehicle.mismatch_bounds, flight.seed))
      .rotor_drag_D_per_s;
}

struct DragIdentification {
  sim::TrackingFlightParams flight;  // the identification flight (two loops, F.7.3)
  int evaluations = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best = Eigen::Vector2d::Zero();  // identified d_x, d_y [1/s]
  std::string nlopt_result;
  std::vector<double> evaluation, best_dx, best_dy, best_E_a;
};

// NLopt objective, x = [d_x, d_y] of the controller's model [1/s].
double DragIdCost(const std::vector<double>& x, std::vector<double>& /*gradient*/, void* data) {
  auto* problem = static_cast<DragIdentification*>(data);
  const Eigen::Vector2d D(x[0], x[1]);
  const double cost = sim::FlyTrackingFlight(WithControllerDrag(problem->flight, D)).error.E_a_m;
  ++problem->evaluations;
  if (cost < problem->best_cost) {
    problem->best_cost = cost;
    problem->best = D;
  }
  problem->evaluation.push_back(problem->evaluations);
  problem->best_dx.push_back(problem->best.x());
  problem->best_dy.push_back(problem->best.y());
  problem->best_E_a.push_back(problem->best_cost);
  return cost;
}

// F.6, F.7.3: Nelder-Mead over (d_x, d_y) from the drag-free model, each cost evaluation one
// SITL flight of two loops of `trajectory` with cost E_a (F.39).
DragIdentification IdentifyDrag(const std::string& trajectory, const ControlBenchOptions& options) {
  DragIdentification problem;
  problem.flight = FullSpeedFlight(MakeReference(trajectory, options.quick ? 1.0 : 2.0), options);
  nlopt::opt optimizer(nlopt::LN_NELDERMEAD, 2);
  optimizer.set_min_objective(DragIdCost, &problem);
  optimizer.set_lower_bounds({0.0, 0.0});
  optimizer.set_upper_bounds({2.0, 2.0});
  optimizer.set_initial_step({0.3, 0.3});
  // 5e-3 1/s is 1-1.5 % of the coefficients; the thesis converged after ~70 flights.
  optimizer.set_xtol_abs(options.quick ? 0.01 : 5e-3);
  optimizer.set_maxeval(options.quick ? 20 : 80);
  std::vector<double> x = {0.0, 0.0};
  double cost = 0.0;
  try {
    switch (optimizer.optimize(x, cost)) {
      case nlopt::XTOL_REACHED:
        problem.nlopt_result = "xtol_reached";
        break;
      case nlopt::FTOL_REACHED:
        problem.nlopt_result = "ftol_reached";
        break;
      case nlopt::MAXEVAL_REACHED:
        problem.nlopt_result = "maxeval_reached";
        break;
      default:
        problem.nlopt_result = "success";
        break;
    }
  } catch (const nlopt::roundoff_limited&) {
    problem.nlopt_result = "roundoff_limited";
  }
  return problem;
}

// Figs. F.6, F.7: the F.7 speed ramp (maximum speed 0 -> 5 m/s linearly in 30 s), error over the
// reference speed without drag and with the coefficients identified on this trajectory; keys
// ramp_E_a_off, ramp_E_a_on over the ramp.
void RunSpeedRamp(const std::string& name, const Eigen::Vector2d& D_xy_per_s,
                  const ControlBenchOptions& options, nlohmann::json* out,
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
    params.control.position.compensate_rotor_drag = false;
    if (compensate) params = WithControllerDrag(params, D_xy_per_s);
    const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);
    const std::string tag = compensate ? "on" : "off";
    (*out)["ramp_E_a_" + tag] = flight.error.E_a_m;
    std::vector<double> speed, error;
    for (size_t k = 0; k < flight.sitl.trajectory.size(); ++k) {
      speed.push_back(flight.reference[k].v_W.norm());
      error.push_back((flight.sitl.trajectory[k].p_WB - flight.reference[k].p_W).norm());
    }
    plot.AddLine(compensate ? "D identified on the " + name : "drag not considered", speed, error);
  }
  report->AddSvg(plot.Render());
}

// Table F.1 of the thesis [cm]: max, sigma of |E_p| and E_a over ten loops, per trajectory and
// parameter identification.
struct ThesisRow {
  const char* trajectory;
  const char* params_id;
  double max_cm, sigma_cm, E_a_cm;
};
constexpr ThesisRow kTableF1[] = {
    {"circle", "not_considered", 21.08, 2.11, 17.53},
    {"circle", "identified_on_circle", 14.54, 2.63, 6.54},
    {"circle", "identified_on_lemniscate", 12.39, 2.53, 8.16},
    {"lemniscate", "not_considered", 16.79, 3.19, 11.27},
    {"lemniscate", "identified_on_circle", 10.25, 2.30, 5.56},
    {"lemniscate", "identified_on_lemniscate", 10.02, 2.23, 5.51},
};

void ReportIdentification(const std::map<std::string, DragIdentification>& identified,
                          const Eigen::Vector3d& true_D, const ControlBenchOptions& options,
                          nlohmann::json* out, output::HtmlReport* report) {
  (*out)["true"] = {{"dx", true_D.x()}, {"dy", true_D.y()}};
  output::SvgPlot coefficients(
      {"Best drag coefficients per evaluation (Fig. F.3 analog)", "evaluation", "d [1/s]"});
  output::SvgPlot costs({"Best E_a per evaluation", "evaluation", "E_a [m]"});
  int most_evaluations = 1;
  for (const auto& [name, id] : identified) {
    (*out)[name] = {
        {"dx", id.best.x()},
        {"dy", id.best.y()},
        {"relative_error",
         {{"dx", id.best.x() / true_D.x() - 1.0}, {"dy", id.best.y() / true_D.y() - 1.0}}},
        {"evaluations", id.evaluations},
        {"E_a", id.best_cost},
        {"nlopt_result", id.nlopt_result}};
    coefficients.AddLine(name + " d_x", id.evaluation, id.best_dx);
    coefficients.AddLine(name + " d_y", id.evaluation, id.best_dy);
    costs.AddLine(name, id.evaluation, id.best_E_a);
    most_evaluations = std::max(most_evaluations, id.evaluations);
  }
  coefficients.AddLine("simulated d_x", {1.0, double(most_evaluations)}, {true_D.x(), true_D.x()});
  coefficients.AddLine("simulated d_y", {1.0, double(most_evaluations)}, {true_D.y(), true_D.y()});
  report->AddSection("Rotor-drag identification (thesis F.6, F.7.3)");
  report->AddParagraph(
      "Nelder-Mead (NLopt LN_NELDERMEAD) over the controllers' d_x, d_y (d_z = k_h = 0), on the "
      "circle and on the lemniscate separately, each evaluation one SITL flight of " +
      std::string(options.quick ? "one loop" : "two loops") +
      " with cost E_a (F.39), starting from the drag-free model. 'simulated' is the vehicle's own "
      "D in hover (with vehicle.mismatch its drag also grows with thrust and has a quadratic part, "
      "which the identified D absorbs).");
  report->AddSvg(coefficients.Render());
  report->AddSvg(costs.Render());
  report->AddTable(*out, "identified drag coefficients [1/s], E_a at the estimate [m]");
}

void RunDrag(const ControlBenchOptions& options, nlohmann::json* summary,
             output::HtmlReport* report) {
  nlohmann::json& drag = (*summary)["drag"];
  std::map<std::string, DragIdentification> identified;
  for (const std::string name : {"circle", "lemniscate"}) {
    identified.emplace(name, IdentifyDrag(name, options));
  }
  ReportIdentification(identified, SimulatedVehicleD(identified.at("circle").flight, options),
                       options, &drag["identified"], report);

  report->AddSection("Rotor-drag compensation (thesis F.7.4, Table F.1)");
  report->AddParagraph(
      "As Table F.1: each trajectory flown " +
      std::string(options.quick ? "one loop" : "ten loops") +
      " at full speed without considering drag and with the coefficients identified on the "
      "circle and on the lemniscate; max and sigma of |E_p| and E_a (F.39) over the full-speed "
      "loops, on the bench vehicle (see 'Simulated vehicle'), IMU noise, ground truth at 100 Hz "
      "with the vehicle's latency uncompensated (the thesis: 55 Hz, 32 ms compensated). The row "
      "'nominal_model' (not in the thesis) compensates the controllers' nominal D.");
  const double loops = options.quick ? 1.0 : 10.0;  // Table F.1: ten loops
  nlohmann::json table = nlohmann::json::array();
  for (const std::string name : {"circle", "lemniscate"}) {
    const auto reference = MakeReference(name, loops);
    nlohmann::json& out = drag[name];
    output::SvgPlot paths({name + ": x-y path (Figs. F.4, F.5 analog)", "x [m]", "y [m]"});
    output::SvgPlot errors(
        {name + ": position error (Figs. F.6, F.7 analog)", "t [s]", "|p - p_ref| [m]"});
    const sim::TrackingFlightParams base = FullSpeedFlight(reference, options);
    std::vector<std::pair<std::string, sim::TrackingFlightParams>> rows;
    sim::TrackingFlightParams not_considered = base;
    not_considered.control.position.compensate_rotor_drag = false;
    rows.emplace_back("not_considered", not_considered);
    for (const auto& [id_name, id] : identified) {
      rows.emplace_back("identified_on_" + id_name, WithControllerDrag(base, id.best));
    }
    sim::TrackingFlightParams nominal = base;
    nominal.control.position.compensate_rotor_drag = true;
    rows.emplace_back("nominal_model", nominal);
    for (size_t r = 0; r < rows.size(); ++r) {
      const auto& [row, params] = rows[r];
      const sim::TrackingFlightResult flight = sim::FlyTrackingFlight(params);
      out[row] = {
          {"E_a", flight.error.E_a_m}, {"max", flight.error.max_m}, {"std", flight.error.std_m}};
      nlohmann::json line = {{"trajectory", name},
                             {"params_id", row},
                             {"max_cm", 100.0 * flight.error.max_m},
                             {"sigma_cm", 100.0 * flight.error.std_m},
                             {"E_a_cm", 100.0 * flight.error.E_a_m}};
      for (const ThesisRow& thesis : kTableF1) {
        if (name == thesis.trajectory && row == thesis.params_id) {
          line["thesis_max_cm"] = thesis.max_cm;
          line["thesis_sigma_cm"] = thesis.sigma_cm;
          line["thesis_E_a_cm"] = thesis.E_a_cm;
        }
      }
      table.push_back(line);
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
      if (r == 0) paths.AddLine("reference", x_ref, y_ref);
      paths.AddLine(row, x, y);
      errors.AddLine(row, t, e);
    }
    // The thesis' comparison: not considered vs identified on the flown trajectory.
    const nlohmann::json& on = out["identified_on_" + name];
    out["E_a_off"] = out["not_considered"]["E_a"];
    out["max_off"] = out["not_considered"]["max"];
    out["E_a_on"] = on["E_a"];
    out["max_on"] = on["max"];
    out["reduction"] = 1.0 - on["E_a"].get<double>() / out["E_a_off"].get<double>();
    report->AddSvg(paths.Render());
    report->AddSvg(errors.Render());
    if (!options.quick) RunSpeedRamp(name, identified.at(name).best, options, &out, report);
  }
  report->AddTable(table, "Table F.1 analog [cm] beside the thesis' values");
  drag["table_f1"] = table;
}

}  // namespace

ControlBenchSection MakeDragSection() { return {"drag", RunDrag}; }

}  // namespace aperture::experiments
