// Narrow-gap planning (seed 000 Sec. II): motion primitive generation + cost, its input-
// feasibility test, one full approach candidate (primitive + feasibility + view angle (9) at every
// sample + cost (10)), the whole candidate grid, one replanning step and the traverse
// optimisation (6). Targets: >= 1e6 candidates/s single-threaded, replanning <= 20 us, traverse
// <= 5 ms (the paper reports 0.24 ms per candidate and 0.018 ms per replanning step onboard).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <vector>

#include "control/constants.h"
#include "planning/approach_planner.h"

namespace aperture::planning {
namespace {

using control::kPi;

GapPose Gap(double roll_deg, double pitch_deg) {
  Eigen::Matrix3d R0;
  R0 << Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX();
  GapPose gap;
  gap.p_WG = Eigen::Vector3d(5.0, 0.5, 1.8);
  gap.R_WG = (Eigen::AngleAxisd(pitch_deg * kPi / 180.0, Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(roll_deg * kPi / 180.0, Eigen::Vector3d::UnitX()))
                 .toRotationMatrix() *
             R0;
  return gap;
}

ApproachTarget Target() {
  return ApproachTarget::FromTraverse(*OptimizeTraverseTrajectory(Gap(30.0, 0.0), {}).trajectory);
}

// The default grid's starts and durations, cycled so branches see varied candidates.
struct CandidateInputs {
  std::vector<Eigen::Vector3d> starts;
  std::vector<double> durations;
};

CandidateInputs Inputs(const ApproachPlanner& planner, const ApproachTarget& target) {
  CandidateInputs inputs;
  const ApproachPlannerParameters& p = planner.parameters();
  for (int n = 0; n < p.duration_count; ++n) {
    for (int i = 0; i < p.start_counts[0]; ++i) {
      for (int j = 0; j < p.start_counts[1]; ++j) {
        for (int l = 0; l < p.start_counts[2]; ++l) {
          inputs.starts.push_back(planner.StartPosition(target, i, j, l));
          inputs.durations.push_back(planner.Duration(n));
        }
      }
    }
  }
  return inputs;
}

void BM_PrimitiveGenerationAndCost(benchmark::State& state) {
  const ApproachTarget target = Target();
  const ApproachPlanner planner{ApproachPlannerParameters()};
  const CandidateInputs inputs = Inputs(planner, target);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ % inputs.starts.size();
    const MotionPrimitive primitive(inputs.starts[k], zero, zero, target.p_W, target.v_W,
                                    target.a_W, inputs.durations[k]);
    benchmark::DoNotOptimize(primitive.Cost());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PrimitiveGenerationAndCost);

void BM_PrimitiveFeasibility(benchmark::State& state) {
  const ApproachTarget target = Target();
  const ApproachPlanner planner{ApproachPlannerParameters()};
  const CandidateInputs inputs = Inputs(planner, target);
  std::vector<MotionPrimitive> primitives;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < inputs.starts.size(); ++k) {
    primitives.emplace_back(inputs.starts[k], zero, zero, target.p_W, target.v_W, target.a_W,
                            inputs.durations[k]);
  }
  const FeasibilityLimits limits;
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(CheckInputFeasibility(primitives[i++ % primitives.size()], limits));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PrimitiveFeasibility);

// One candidate with all the work of the paper's Sec. V-B list (i)-(iv): generation, feasibility,
// the view angle at every sample (argument: samples per candidate, default 20) and the cost (10).
void BM_ApproachCandidate(benchmark::State& state) {
  const ApproachTarget target = Target();
  ApproachPlannerParameters parameters;
  parameters.samples_per_candidate = static_cast<int>(state.range(0));
  const ApproachPlanner planner(parameters);
  const CandidateInputs inputs = Inputs(planner, target);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ % inputs.starts.size();
    benchmark::DoNotOptimize(
        planner.EvaluateCandidate(target, inputs.starts[k], inputs.durations[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ApproachCandidate)->Arg(2)->Arg(10)->Arg(20);

// The whole default grid (7 x 7 x 5 starts x 8 durations = 1960 candidates); items = candidates.
void BM_ApproachPlan(benchmark::State& state) {
  const ApproachTarget target = Target();
  const ApproachPlanner planner{ApproachPlannerParameters()};
  int64_t candidates = 0;
  for (auto _ : state) {
    const ApproachPlan plan = planner.Plan(target);
    candidates += plan.candidates;
    benchmark::DoNotOptimize(plan);
  }
  state.SetItemsProcessed(candidates);
}
BENCHMARK(BM_ApproachPlan)->Unit(benchmark::kMicrosecond);

// One replanning step from states along the planned approach (perturbed by 5 cm / 0.1 m/s as an
// estimator update would), remaining time shrinking to 0.2 s.
void BM_Replan(benchmark::State& state) {
  const ApproachTarget target = Target();
  const ApproachPlanner planner{ApproachPlannerParameters()};
  const MotionPrimitive plan = planner.Plan(target).best->primitive;
  std::vector<Eigen::Vector3d> p, v, a;
  std::vector<double> remaining;
  for (int k = 0; k < 64; ++k) {
    const double t = (plan.duration_s() - 0.2) * k / 64.0;
    const double sign = (k % 2 == 0) ? 1.0 : -1.0;
    p.push_back(plan.Position(t) + sign * Eigen::Vector3d(0.05, -0.03, 0.02));
    v.push_back(plan.Velocity(t) + sign * Eigen::Vector3d(0.1, 0.05, -0.05));
    a.push_back(plan.Acceleration(t));
    remaining.push_back(plan.duration_s() - t);
  }
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 63;
    benchmark::DoNotOptimize(planner.Replan(target, p[k], v[k], a[k], remaining[k]));
  }
}
BENCHMARK(BM_Replan);

void BM_TraverseOptimization(benchmark::State& state) {
  const std::vector<GapPose> gaps = {Gap(20.0, 0.0), Gap(45.0, 0.0), Gap(30.0, 30.0),
                                     Gap(45.0, -20.0)};
  const TraverseParameters parameters;
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(OptimizeTraverseTrajectory(gaps[i++ % gaps.size()], parameters));
  }
}
BENCHMARK(BM_TraverseOptimization)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::planning
