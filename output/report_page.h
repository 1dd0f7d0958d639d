#pragma once
// The end of a command's report.html, the same for every bench: the outcome on top, what was run
// (HtmlReport::AddRunDescription from the summary and the wall time so far), every figure of
// summary.json folded at the bottom, written atomically to OUT/report.html.
//
//   output::HtmlReport report("aperture bench led");
//   ... sections ...
//   output::WriteReportPage(report, output::AcceptanceOutcome(out.summary()["acceptance"]), out);
#include "output/html_report.h"
#include "output/output_folder.h"

namespace aperture::output {

// Returns the path written.
std::string WriteReportPage(HtmlReport& report, const ReportOutcome& outcome,
                            const OutputFolder& out);

}  // namespace aperture::output
