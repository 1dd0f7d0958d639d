// A bench section recorded as one trial (experiments/bench/section_record.h) and written back
// after a trip through CBOR, as a merge of shards does: the same summary figures, report blocks
// and CSV rows as writing it in the process that ran it.
#include "experiments/bench/section_record.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "output/svg_plot.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::experiments {
namespace {

// Two sections that write under their own keys and one shared parent ("acceptance").
void RunFirst(nlohmann::json* summary, output::HtmlReport* report) {
  (*summary)["first"] = {{"error_m", 0.1 + 0.2}, {"nan", std::nan("")}};
  (*summary)["acceptance"]["first_ok"] = true;
  report->AddSection("First");
  report->AddSvg(output::SvgPlot({"plot", "x", "y"}).AddLine("line", {0, 1}, {1, 0}).Render());
}
void RunSecond(nlohmann::json* summary, output::HtmlReport* report) {
  (*summary)["second"] = {{"frames", 3}};
  (*summary)["acceptance"]["second_ok"] = false;
  report->AddTable((*summary)["second"], "second");
}

nlohmann::json ThroughCbor(const nlohmann::json& record) {
  return nlohmann::json::from_cbor(nlohmann::json::to_cbor(record));
}

TEST(SectionRecord, RecordsThroughCborWriteWhatTheSectionsWrote) {
  nlohmann::json direct_summary = nlohmann::json::object();
  output::HtmlReport direct("bench");
  RunFirst(&direct_summary, &direct);
  RunSecond(&direct_summary, &direct);

  nlohmann::json merged_summary = nlohmann::json::object();
  output::HtmlReport merged("bench");
  for (const SectionRun& run : {SectionRun(RunFirst), SectionRun(RunSecond)}) {
    const nlohmann::json record = RecordSection(run);
    EXPECT_GE(record["wall_time_s"].get<double>(), 0.0);
    AddSectionRecord(ThroughCbor(record), &merged_summary, &merged);
  }
  // Shared parents merge key by key; JSON text of a double is its shortest exact form.
  EXPECT_EQ(merged_summary.dump(), direct_summary.dump());
  EXPECT_TRUE(std::isnan(merged_summary["first"]["nan"].get<double>()));
  EXPECT_EQ(merged_summary["acceptance"].size(), 2u);
  EXPECT_EQ(merged.blocks(), direct.blocks());
  EXPECT_EQ(merged.ToHtml(), direct.ToHtml());
}

class SectionRecordCsvTest : public aperture::testing::TempDirectoryTest {};

TEST_F(SectionRecordCsvTest, RecordedRowsWriteTheSameCsvAsDirectCells) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string direct_path = (directory_ / "direct.csv").string();
  const std::string recorded_path = (directory_ / "recorded.csv").string();
  {
    output::CsvWriter csv(direct_path, {"section", "t_s", "error_m"});
    csv.WriteCells({std::string("a,b"), 0.1, nan});
    csv.WriteCells({std::string("c"), 1e-310, 0.30000000000000004});
  }
  {
    output::CsvWriter csv(recorded_path, {"section", "t_s", "error_m"});
    const nlohmann::json rows = {{"a,b", 0.1, nan}, {"c", 1e-310, 0.30000000000000004}};
    WriteRecordedCsvRows(ThroughCbor(rows), &csv);
  }
  const auto text = [](const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  EXPECT_EQ(text(recorded_path), text(direct_path));
}

}  // namespace
}  // namespace aperture::experiments
