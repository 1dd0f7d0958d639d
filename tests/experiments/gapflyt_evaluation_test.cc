// The GapFlyt evaluator on constructed flights through a known opening: the crossing, the
// clearance of the footprint, the offset from the centroid and the verdicts, hand-computed.
#include "experiments/gapflyt/gapflyt_evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"
#include "sim/scenario/scenario.h"

namespace aperture::experiments {
namespace {

// A 1 m x 0.8 m rectangular opening in the wall x_W = 2.6 m, centred at y = 0, z = 1.5 m, facing
// +x_W as the scenario's walls do (x_O = -y_W right, y_O = -z_W down, z_O = +x_W).
GapflytOpening Box() {
  GapflytOpening opening;
  const Eigen::Matrix3d R_WO = perception::OpticalAxesAlongX();
  opening.T_WO.linear() = R_WO;
  opening.T_WO.translation() = Eigen::Vector3d(2.6, 0.0, 1.5);
  opening.polygon_O = {{-0.5, -0.4}, {0.5, -0.4}, {0.5, 0.4}, {-0.5, 0.4}};
  return opening;
}

// Level flight along +x_W at 1 m/s through (y, z), sampled at 100 Hz from x = 0 to x_end.
sim::SitlResult StraightGapflytFlight(double y, double z, double x_end = 4.0) {
  sim::SitlResult result;
  for (int k = 0; k * 0.01 <= x_end + 1e-9; ++k) {
    control::QuadState state;
    state.t_s = k * 0.01;
    state.p_WB = Eigen::Vector3d(k * 0.01, y, z);
    state.v_W = Eigen::Vector3d(1.0, 0.0, 0.0);
    result.trajectory.push_back(state);
  }
  return result;
}

TEST(GapflytEvaluationTest, CentredCrossingPassesWithTheFootprintsClearance) {
  const control::VehicleParameters vehicle;
  const sim::CollisionParams collision;
  const GapflytEvaluation e =
      EvaluateGapflytFlight(StraightGapflytFlight(0.0, 1.5), Box(), vehicle, collision);
  ASSERT_TRUE(e.passed) << e.failure_reason;
  ASSERT_TRUE(e.crossing);
  EXPECT_NEAR(e.crossing->t_s, 2.6, 1e-9);  // x = 2.6 m at 1 m/s
  EXPECT_NEAR(e.crossing->p_O.norm(), 0.0, 1e-9);
  EXPECT_NEAR(e.crossing->centre_to_edge_m, 0.4, 1e-9);  // the nearer (horizontal) edges
  // Level X-configuration: rotors at (+-a, +-a) / sqrt(2) in B, so in the wall plane at a lateral
  // offset a / sqrt(2) and height 0: a rotor disk is 0.5 - a / sqrt(2) - r_p from a side edge and
  // 0.4 - r_p from the top and bottom; the body sphere 0.4 - r_b from the top and bottom.
  const double rotor_lateral = vehicle.arm_length_m / std::sqrt(2.0);
  const double expected =
      std::min({0.4 - collision.body_radius_m, 0.5 - rotor_lateral - collision.propeller_radius_m,
                0.4 - collision.propeller_radius_m});
  EXPECT_NEAR(e.crossing->clearance_m, expected, 1e-9);
  EXPECT_NEAR(e.crossing->offset_from_centroid_m.norm(), 0.0, 1e-9);
}

TEST(GapflytEvaluationTest, OffsetCrossingReportsTheOffsetAndTheSideClearance) {
  const control::VehicleParameters vehicle;
  const sim::CollisionParams collision;
  // 0.3 m to the left of the centre (+y_W = -x_O): 0.2 m to the left edge.
  const GapflytEvaluation e =
      EvaluateGapflytFlight(StraightGapflytFlight(0.3, 1.5), Box(), vehicle, collision);
  ASSERT_TRUE(e.passed);
  EXPECT_NEAR(e.crossing->offset_from_centroid_m.x(), -0.3, 1e-9);
  EXPECT_NEAR(e.crossing->offset_from_centroid_m.y(), 0.0, 1e-9);
  EXPECT_NEAR(e.crossing->centre_to_edge_m, 0.2, 1e-9);
  const double rotor_lateral = vehicle.arm_length_m / std::sqrt(2.0);
  EXPECT_NEAR(e.crossing->clearance_m, 0.2 - rotor_lateral - collision.propeller_radius_m, 1e-9);
}

TEST(GapflytEvaluationTest, FailuresNameTheirReason) {
  const control::VehicleParameters vehicle;
  const sim::CollisionParams collision;
  // Beside the opening (the wall is not in this constructed run, so no collision either).
  GapflytEvaluation e =
      EvaluateGapflytFlight(StraightGapflytFlight(0.8, 1.5), Box(), vehicle, collision);
  EXPECT_FALSE(e.passed);
  EXPECT_EQ(e.failure_reason, "crossed the wall plane outside the opening");
  EXPECT_LT(e.crossing->centre_to_edge_m, 0.0);
  // Stopped before the wall.
  e = EvaluateGapflytFlight(StraightGapflytFlight(0.0, 1.5, 2.0), Box(), vehicle, collision);
  EXPECT_FALSE(e.passed);
  EXPECT_EQ(e.failure_reason, "did not cross the wall plane");
  // Through the centre but with a collision in the run.
  sim::SitlResult hit = StraightGapflytFlight(0.0, 1.5);
  hit.collision = sim::Collision{"gap", "propeller 1", Eigen::Vector3d(2.6, 0.5, 1.5)};
  e = EvaluateGapflytFlight(hit, Box(), vehicle, collision);
  EXPECT_FALSE(e.passed);
  EXPECT_EQ(e.failure_reason, "collision with 'gap'");
}

TEST(GapflytEvaluationTest, OpeningFromTheScenariosWallMatchesItsParameters) {
  for (const std::string shape : {"ellipse", "triangle"}) {
    sim::ScenarioParams params = sim::LoadScenarioParams(
        sim::ScenarioConfig("gapflyt", {}, {"gapflyt.shape=" + shape, "gapflyt.size_m=[1.0,0.8]"}));
    const sim::Scenario scenario = sim::BuildScenario(params);
    const GapflytOpening opening = OpeningFromScene(scenario.scene());
    EXPECT_NEAR((opening.T_WO.translation() - Eigen::Vector3d(2.6, 0.0, 1.5)).norm(), 0.0, 1e-9);
    if (shape == "ellipse") {
      // Centre of a 64-gon inscribed in the 0.5 x 0.4 ellipse: 0.4 cos(pi/64) from its edge.
      EXPECT_NEAR(opening.Centroid().norm(), 0.0, 1e-9);
      EXPECT_NEAR(opening.SignedDistance({0.0, 0.0}), 0.4, 0.002);
    } else {
      // Isosceles, apex up (y_O down): centroid 1/3 of the height above the base.
      EXPECT_NEAR(opening.Centroid().y(), 0.4 - 0.8 / 3.0, 1e-9);
      EXPECT_LT(opening.SignedDistance({0.0, -0.39}), 0.01);  // just below the apex
    }
  }
  sim::ScenarioParams gap = sim::LoadScenarioParams(sim::ScenarioConfig("gap"));
  const sim::Scenario no_opening = sim::BuildScenario(gap);
  EXPECT_THROW(OpeningFromScene(no_opening.scene(), "ground"), std::invalid_argument);
}

TEST(GapflytEvaluationTest, DetectionScoreAgainstTheProjectedOpening) {
  const perception::PinholeCamera camera(320, 240, {200.0, 200.0, 159.5, 119.5});
  // Camera 2 m in front of the opening's centre, looking at it along +x_W.
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() = Box().T_WO.linear();  // camera axes = wall axes (x right, y down, z forward)
  T_WC.translation() = Eigen::Vector3d(0.6, 0.0, 1.5);
  // The opening spans 1.0 / 2 * 200 = 100 px by 80 px around the principal point.
  cv::Mat exact = cv::Mat::zeros(240, 320, CV_8UC1);
  cv::rectangle(exact, cv::Point(110, 80), cv::Point(209, 159), cv::Scalar(255), cv::FILLED);
  const perception::OpeningScore score = ScoreGapflytDetection(exact, Box(), camera, T_WC);
  EXPECT_GT(score.overlap, 0.97);
  EXPECT_LT(score.false_positive, 0.01);
  // Half of it: overlap ~0.5, not a detection.
  cv::Mat half = cv::Mat::zeros(240, 320, CV_8UC1);
  cv::rectangle(half, cv::Point(110, 80), cv::Point(159, 159), cv::Scalar(255), cv::FILLED);
  const perception::OpeningScore half_score = ScoreGapflytDetection(half, Box(), camera, T_WC);
  EXPECT_NEAR(half_score.overlap, 0.5, 0.03);
  EXPECT_FALSE(half_score.detected());
  // Camera behind the wall looking away: the opening is not in view.
  T_WC.translation().x() = 3.0;
  EXPECT_THROW(ScoreGapflytDetection(exact, Box(), camera, T_WC), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
