// The drag section of `aperture bench control` (Table F.1 protocol) in quick mode (one loop per
// flight, at most 20 identification flights per trajectory).
#include "experiments/control/drag_sections.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture::experiments {
namespace {

ControlBenchOptions Quick() {
  ControlBenchOptions options;
  options.quick = true;
  options.vehicle.mismatch = false;  // vehicle = model: D is then identifiable exactly
  return options;
}

TEST(DragSectionsTest, IdentifiedDragCutsTheTrackingErrorOnBothTrajectories) {
  const ControlBenchSection section = MakeDragSection();
  EXPECT_EQ(section.key, "drag");
  nlohmann::json summary;
  output::HtmlReport report("test");
  section.run(Quick(), &summary, &report);
  for (const char* name : {"circle", "lemniscate"}) {
    const nlohmann::json& drag = summary["drag"][name];
    const double off = drag["E_a_off"].get<double>();
    const double on = drag["E_a_on"].get<double>();
    EXPECT_EQ(off, drag["not_considered"]["E_a"].get<double>()) << name;
    EXPECT_EQ(on, drag[std::string("identified_on_") + name]["E_a"].get<double>()) << name;
    // Issue 4 acceptance: at least 50 % lower E_a with compensation (Table F.1: 63 %, 51 %).
    EXPECT_LT(on, 0.5 * off) << name;
    // Uncompensated drag leaves centimetres to decimetres (Table F.1: 11-18 cm).
    EXPECT_GT(off, 0.05) << name;
    EXPECT_NEAR(drag["reduction"].get<double>(), 1.0 - on / off, 1e-12) << name;
    // Every row: sigma(|E_p|) <= E_a = rms|E_p| <= max|E_p| (by definition).
    for (const char* row :
         {"not_considered", "identified_on_circle", "identified_on_lemniscate", "nominal_model"}) {
      const nlohmann::json& r = drag[row];
      EXPECT_LE(r["std"].get<double>(), r["E_a"].get<double>()) << name << " " << row;
      EXPECT_LE(r["E_a"].get<double>(), r["max"].get<double>()) << name << " " << row;
      EXPECT_GT(r["std"].get<double>(), 0.0) << name << " " << row;
    }
  }
  const nlohmann::json& table = summary["drag"]["table_f1"];
  ASSERT_EQ(table.size(), 8u);
  EXPECT_EQ(table[1]["params_id"], "identified_on_circle");
  EXPECT_DOUBLE_EQ(table[1]["thesis_E_a_cm"].get<double>(), 6.54);  // Table F.1, circle row 2
  EXPECT_NE(report.ToHtml().find("x-y path"), std::string::npos);

  // The identification flights (Nelder-Mead from d = 0) recover the vehicle's D.
  const nlohmann::json& id = summary["drag"]["identified"];
  EXPECT_EQ(id["true"]["dx"].get<double>(), 0.5);
  EXPECT_EQ(id["true"]["dy"].get<double>(), 0.35);
  // Quick mode (one loop per flight, at most 20 flights from d = 0, x tolerance 0.01 1/s) ends
  // at (0.518, 0.343) on the circle, 4 % / 2 % off; the bound 0.035 1/s is 7 % of d_x and 10 % of
  // d_y (the acceptance of issue 4; the full run's 80 flights at 5e-3 tolerance reach < 1 %).
  EXPECT_NEAR(id["circle"]["dx"].get<double>(), 0.5, 0.035);
  EXPECT_NEAR(id["circle"]["dy"].get<double>(), 0.35, 0.035);
  for (const char* name : {"circle", "lemniscate"}) {
    EXPECT_LE(id[name]["evaluations"].get<int>(), 20) << name;
    EXPECT_GT(id[name]["evaluations"].get<int>(), 3) << name;
  }
}

// On the mismatched bench vehicle (issue 21: quadratic and thrust-dependent drag, drag factors,
// latency, ...) compensating the identified drag still cuts E_a, by less. The rows fly the
// identified D, not the controllers' nominal one: the identification lands away from the nominal
// D and its row's error differs from the nominal row's.
TEST(DragSectionsTest, DragCompensationStillCutsTheErrorOnTheMismatchedVehicle) {
  ControlBenchOptions options = Quick();
  options.vehicle.mismatch = true;
  nlohmann::json summary;
  output::HtmlReport report("test");
  MakeDragSection().run(options, &summary, &report);
  for (const char* name : {"circle", "lemniscate"}) {
    const nlohmann::json& drag = summary["drag"][name];
    const double off = drag["E_a_off"].get<double>();
    const double on = drag["E_a_on"].get<double>();
    EXPECT_LT(on, 0.6 * off) << name;
    EXPECT_GT(on, 0.02) << name;  // far from the vehicle = model's few millimetres
    EXPECT_NE(on, drag["nominal_model"]["E_a"].get<double>()) << name;
  }
  const nlohmann::json& circle = summary["drag"]["identified"]["circle"];
  EXPECT_GT(
      std::abs(circle["dx"].get<double>() - 0.5) + std::abs(circle["dy"].get<double>() - 0.35),
      0.02);
  // The circle's identification minimizes the circle's E_a: its row beats the nominal D's.
  EXPECT_LT(summary["drag"]["circle"]["identified_on_circle"]["E_a"].get<double>(),
            summary["drag"]["circle"]["nominal_model"]["E_a"].get<double>());
}

}  // namespace
}  // namespace aperture::experiments
