#include "output/report_page.h"

#include <string>

namespace aperture::output {

std::string WriteReportPage(HtmlReport& report, const ReportOutcome& outcome,
                            const OutputFolder& out) {
  report.AddOutcome(outcome);
  report.AddRunDescription(out.summary(), out.ElapsedSeconds());
  report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
  const std::string path = out.Path("report.html");
  report.Write(path);
  return path;
}

}  // namespace aperture::output
