// The drag and drag_id sections of `aperture bench control` in quick mode (one loop per flight).
#include "experiments/control/drag_sections.h"

#include <gtest/gtest.h>

namespace aperture::experiments {
namespace {

ControlBenchOptions Quick() {
  ControlBenchOptions options;
  options.quick = true;
  options.vehicle.mismatch = false;  // vehicle = model: D is then identifiable exactly
  return options;
}

TEST(DragSectionsTest, DragCompensationCutsTheTrackingErrorOnBothTrajectories) {
  const ControlBenchSection section = MakeDragSection();
  EXPECT_EQ(section.key, "drag");
  nlohmann::json summary;
  output::HtmlReport report("test");
  section.run(Quick(), &summary, &report);
  for (const char* name : {"circle", "lemniscate"}) {
    const nlohmann::json& drag = summary["drag"][name];
    const double off = drag["E_a_off"].get<double>();
    const double on = drag["E_a_on"].get<double>();
    // Issue 4 acceptance: at least 50 % lower E_a with compensation (Table F.1: 63 %, 51 %).
    EXPECT_LT(on, 0.5 * off) << name;
    // Uncompensated drag leaves centimetres to decimetres (Table F.1: 11-18 cm).
    EXPECT_GT(off, 0.05) << name;
    EXPECT_NEAR(drag["reduction"].get<double>(), 1.0 - on / off, 1e-12) << name;
  }
  EXPECT_NE(report.ToHtml().find("x-y path"), std::string::npos);
}

// On the mismatched bench vehicle (issue 21: quadratic and thrust-dependent drag, drag factors,
// latency, ...) compensating the nominal model's drag still cuts E_a, by less (seeds 1-3 in
// quick mode: 50-57 %; Table F.1: 63 %, 51 %).
TEST(DragSectionsTest, DragCompensationStillCutsTheErrorOnTheMismatchedVehicle) {
  ControlBenchOptions options = Quick();
  options.vehicle.mismatch = true;
  nlohmann::json summary;
  output::HtmlReport report("test");
  MakeDragSection().run(options, &summary, &report);
  for (const char* name : {"circle", "lemniscate"}) {
    const double off = summary["drag"][name]["E_a_off"].get<double>();
    const double on = summary["drag"][name]["E_a_on"].get<double>();
    EXPECT_LT(on, 0.6 * off) << name;
    EXPECT_GT(on, 0.02) << name;  // far from the vehicle = model's few millimetres
  }
}

TEST(DragSectionsTest, NelderMeadRecoversTheDragCoefficients) {
  const ControlBenchSection section = MakeDragIdSection();
  EXPECT_EQ(section.key, "drag_id");
  nlohmann::json summary;
  output::HtmlReport report("test");
  section.run(Quick(), &summary, &report);
  const nlohmann::json& id = summary["drag_id"];
  EXPECT_EQ(id["true"]["dx"].get<double>(), 0.5);
  EXPECT_EQ(id["true"]["dy"].get<double>(), 0.35);
  // Quick mode (one loop per flight, at most 20 flights from d = 0, x tolerance 0.01 1/s) ends
  // at (0.518, 0.343), 4 % / 2 % off; the bound 0.035 1/s is 7 % of d_x and 10 % of d_y (the
  // acceptance of issue 4; the full run's 80 flights at 5e-3 tolerance reach < 1 %).
  EXPECT_NEAR(id["estimated"]["dx"].get<double>(), 0.5, 0.035);
  EXPECT_NEAR(id["estimated"]["dy"].get<double>(), 0.35, 0.035);
  EXPECT_LE(id["evaluations"].get<int>(), 20);
}

}  // namespace
}  // namespace aperture::experiments
