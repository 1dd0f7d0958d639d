#include "experiments/bench/section_record.h"

#include <chrono>
#include <string>
#include <vector>

namespace aperture::experiments {

nlohmann::json RecordSection(const SectionRun& run) {
  nlohmann::json summary = nlohmann::json::object();
  output::HtmlReport report("");
  const auto start = std::chrono::steady_clock::now();
  run(&summary, &report);
  return {{"summary", summary},
          {"report", report.blocks()},
          {"wall_time_s",
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
}

void AddSectionRecord(const nlohmann::json& record, nlohmann::json* summary,
                      output::HtmlReport* report) {
  summary->update(record.at("summary"), /*merge_objects=*/true);
  report->AddBlocks(record.at("report").get<std::vector<std::string>>());
}

void WriteRecordedCsvRows(const nlohmann::json& rows, output::CsvWriter* csv) {
  for (const nlohmann::json& row : rows) {
    std::vector<output::CsvCell> cells;
    for (const nlohmann::json& cell : row) {
      cells.push_back(cell.is_string() ? output::CsvCell(cell.get<std::string>())
                                       : output::CsvCell(cell.get<double>()));
    }
    csv->WriteCells(cells);
  }
}

}  // namespace aperture::experiments
