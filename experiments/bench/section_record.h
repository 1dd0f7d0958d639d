#pragma once
// A section of a bench made of sections (`bench led`, `bench control`, `bench tags`: each
// section fills its own summary keys and report blocks from its own seeded streams) run as one
// trial of a Monte-Carlo bench (monte_carlo_bench.h). The section writes into an empty summary
// and report; its record keeps both, so the bench's writer puts the section's figures and blocks
// into the whole run's outputs the same way whether it ran in this process or in a shard.
//
//   nlohmann::json record = RecordSection([&](nlohmann::json* summary, output::HtmlReport* report) {
//     RunDrag(options, summary, report);
//   });
//   ...
//   AddSectionRecord(record, &out.summary(), &report);   // in the bench's WriteOutputs
#include <functional>
#include <nlohmann/json.hpp>

#include "output/csv_writer.h"
#include "output/html_report.h"

namespace aperture::experiments {

using SectionRun = std::function<void(nlohmann::json* summary, output::HtmlReport* report)>;

// Runs `run` on an empty summary and report: {"summary": what it wrote, "report": its blocks,
// "wall_time_s": how long it took (a measurement, not a figure)}.
nlohmann::json RecordSection(const SectionRun& run);

// Merges record["summary"] into *summary (objects key by key, so sections may share a parent
// key) and appends record["report"] to *report.
void AddSectionRecord(const nlohmann::json& record, nlohmann::json* summary,
                      output::HtmlReport* report);

// Writes recorded CSV rows (a section's per-frame rows in its record: JSON arrays of strings and
// numbers, NaN kept by CBOR) to *csv, one row per array.
void WriteRecordedCsvRows(const nlohmann::json& rows, output::CsvWriter* csv);

}  // namespace aperture::experiments
