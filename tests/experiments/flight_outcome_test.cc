// Success / safe abort / crash of a fault-sweep flight, on hand-made SITL results.
#include "experiments/faults/flight_outcome.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace aperture::experiments {
namespace {

// 2 s at 100 Hz hovering at 1 m; `last` changes the final 0.2 s.
sim::SitlResult Hover(const std::function<void(control::QuadState*)>& last = {}) {
  sim::SitlResult result;
  for (int k = 0; k <= 200; ++k) {
    control::QuadState state;
    state.t_s = 0.01 * k;
    state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.0);
    if (last && state.t_s > 1.8) last(&state);
    result.trajectory.push_back(state);
  }
  result.sim_time_s = 2.0;
  return result;
}

TEST(FlightOutcome, PassedMissionIsASuccess) {
  const FlightOutcome outcome = ClassifyFlight(true, Hover());
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kSuccess);
  EXPECT_TRUE(outcome.reason.empty());
}

TEST(FlightOutcome, FailedMissionEndingInAStableHoverIsASafeAbort) {
  const FlightOutcome outcome = ClassifyFlight(
      false, Hover([](control::QuadState* s) {
        s->v_W = Eigen::Vector3d(0.3, 0.0, 0.0);  // drifting slowly
        s->q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));  // 11.5 deg
        s->omega_B = Eigen::Vector3d(0.0, 0.0, 2.0);  // turning about z_B is allowed
      }));
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kSafeAbort) << outcome.reason;
  EXPECT_STREQ(ToString(outcome.kind), "safe_abort");
}

TEST(FlightOutcome, CollisionOrUnstableEndIsACrash) {
  sim::SitlResult collided = Hover();
  collided.collision = sim::Collision{};
  collided.reason = "collision: body with 'gap'";
  FlightOutcome outcome = ClassifyFlight(false, collided);
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kCrash);
  EXPECT_EQ(outcome.reason, "collision: body with 'gap'");

  outcome = ClassifyFlight(
      false, Hover([](control::QuadState* s) { s->v_W = Eigen::Vector3d(0.0, 0.8, 0.0); }));
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kCrash);
  EXPECT_NE(outcome.reason.find("speed 0.80 m/s"), std::string::npos) << outcome.reason;

  outcome = ClassifyFlight(
      false, Hover([](control::QuadState* s) {
        s->q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()));  // 34 deg
      }));
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kCrash);
  EXPECT_NE(outcome.reason.find("tilt"), std::string::npos) << outcome.reason;

  outcome = ClassifyFlight(
      false, Hover([](control::QuadState* s) { s->omega_B = Eigen::Vector3d(1.5, 0.0, 0.0); }));
  EXPECT_EQ(outcome.kind, FlightOutcomeKind::kCrash);
  EXPECT_NE(outcome.reason.find("roll/pitch rate"), std::string::npos) << outcome.reason;

  // Unstable before the window only: a recovered vehicle.
  sim::SitlResult recovered = Hover();
  recovered.trajectory[100].v_W = Eigen::Vector3d(3.0, 0.0, 0.0);  // t = 1 s
  EXPECT_EQ(ClassifyFlight(false, recovered).kind, FlightOutcomeKind::kSafeAbort);
}

TEST(FlightOutcome, RunShorterThanTheWindowIsACrash) {
  sim::SitlResult result = Hover();
  result.trajectory.resize(20);  // 0.19 s
  EXPECT_EQ(ClassifyFlight(false, result).kind, FlightOutcomeKind::kCrash);
  EXPECT_EQ(ClassifyFlight(false, sim::SitlResult{}).kind, FlightOutcomeKind::kCrash);
  SafeStateCriteria bad;
  bad.window_s = 0.0;
  EXPECT_THROW(ClassifyFlight(false, Hover(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
