#include "output/html_report.h"

#include <cstdio>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "output/atomic_file.h"
#include "output/base64.h"
#include "output/svg_plot.h"

namespace aperture::output {
namespace {

constexpr const char* kStyle = R"css(
body { font-family: -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif;
       max-width: 960px; margin: 2em auto; padding: 0 1em; color: #222; line-height: 1.45; }
h1 { font-size: 1.6em; border-bottom: 2px solid #444; padding-bottom: 0.2em; }
h2 { font-size: 1.25em; margin-top: 1.8em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.92em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
figure { margin: 1em 0; }
figure svg, figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.9em; color: #555; margin-top: 0.3em; }
caption { caption-side: top; text-align: left; font-weight: bold; padding-bottom: 0.3em; }
.outcome { border: 2px solid #888; border-radius: 6px; padding: 0.2em 1em 0.6em; margin: 1em 0; }
.outcome.passed { border-color: #2a7d2a; background: #f0f8f0; }
.outcome.failed { border-color: #b22222; background: #fbf0f0; }
.outcome h2 { margin-top: 0.4em; border: none; }
details { margin: 0.8em 0; }
summary { cursor: pointer; font-weight: bold; }
)css";

std::string FormatCell(const nlohmann::json& value, bool* is_number) {
  *is_number = value.is_number();
  if (value.is_string()) return EscapeXml(value.get<std::string>());
  if (value.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.6g", value.get<double>());
    return buffer;
  }
  if (value.is_null()) return "&mdash;";
  return EscapeXml(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

void Flatten(const nlohmann::json& object, const std::string& prefix,
             std::vector<std::pair<std::string, nlohmann::json>>* rows) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object() && !it->empty()) {
      Flatten(*it, key, rows);
    } else {
      rows->emplace_back(key, *it);
    }
  }
}

std::string Cell(const nlohmann::json& value) {
  bool is_number = false;
  const std::string text = FormatCell(value, &is_number);
  return std::string(is_number ? "<td class=\"number\">" : "<td>") + text + "</td>";
}

std::string Figure(const std::string& content, const std::string& caption) {
  return "<figure>" + content +
         (caption.empty() ? "" : "<figcaption>" + EscapeXml(caption) + "</figcaption>") +
         "</figure>\n";
}

std::string TableHtml(const nlohmann::json& data, const std::string& caption) {
  std::ostringstream html;
  html << "<table>";
  if (!caption.empty()) html << "<caption>" << EscapeXml(caption) << "</caption>";
  if (data.is_object()) {
    std::vector<std::pair<std::string, nlohmann::json>> rows;
    Flatten(data, "", &rows);
    for (const auto& [key, value] : rows) {
      html << "<tr><th>" << EscapeXml(key) << "</th>" << Cell(value) << "</tr>\n";
    }
  } else if (data.is_array() && !data.empty() && data.front().is_object()) {
    std::vector<std::string> columns;
    std::set<std::string> seen;
    for (const nlohmann::json& row : data) {
      for (auto it = row.begin(); row.is_object() && it != row.end(); ++it) {
        if (seen.insert(it.key()).second) columns.push_back(it.key());
      }
    }
    html << "<tr>";
    for (const std::string& column : columns) html << "<th>" << EscapeXml(column) << "</th>";
    html << "</tr>\n";
    for (const nlohmann::json& row : data) {
      html << "<tr>";
      for (const std::string& column : columns) {
        html << (row.is_object() && row.contains(column) ? Cell(row[column]) : "<td></td>");
      }
      html << "</tr>\n";
    }
  } else {
    html << "<tr>" << Cell(data) << "</tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

}  // namespace

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::AddSection(const std::string& heading) {
  blocks_.push_back("<h2>" + EscapeXml(heading) + "</h2>\n");
}

void HtmlReport::AddParagraph(const std::string& text) {
  blocks_.push_back("<p>" + EscapeXml(text) + "</p>\n");
}

void HtmlReport::AddTable(const nlohmann::json& data, const std::string& caption) {
  blocks_.push_back(TableHtml(data, caption));
}

void HtmlReport::AddCollapsedTable(const nlohmann::json& data, const std::string& label) {
  blocks_.push_back("<details><summary>" + EscapeXml(label) + "</summary>\n" + TableHtml(data, "") +
                    "</details>\n");
}

void HtmlReport::AddOutcome(const ReportOutcome& outcome) {
  std::string html = "<section class=\"outcome " + EscapeXml(outcome.verdict) +
                     "\"><h2>Outcome: " + EscapeXml(outcome.verdict) + "</h2>\n<p>" +
                     EscapeXml(outcome.headline) + "</p>\n";
  if (!outcome.figures.empty()) {
    html += "<table><tr><th>figure</th><th>value</th><th>target</th></tr>\n";
    for (const ReportFigure& figure : outcome.figures) {
      html += "<tr><td>" + EscapeXml(figure.name) + "</td><td>" + EscapeXml(figure.value) +
              "</td><td>" + EscapeXml(figure.target) + "</td></tr>\n";
    }
    html += "</table>\n";
  }
  outcome_html_ = html + "</section>\n";
}

void HtmlReport::AddRunDescription(const nlohmann::json& summary, double wall_time_s) {
  char wall_time[64];
  std::snprintf(wall_time, sizeof(wall_time), "%.1f s", wall_time_s);
  nlohmann::json run = {{"command", "aperture " + summary.value("command", std::string("?"))},
                        {"wall time", wall_time}};
  if (summary.contains("inputs")) run["inputs"] = summary["inputs"];
  run_html_ = "<h2>What was run</h2>\n" + TableHtml(run, "");
  if (summary.contains("config")) {
    run_html_ += "<details><summary>Configuration (every effective parameter)</summary>\n" +
                 TableHtml(summary["config"], "") + "</details>\n";
  }
}

void HtmlReport::AddSvg(const std::string& svg, const std::string& caption) {
  blocks_.push_back(Figure(svg, caption));
}

void HtmlReport::AddImage(const cv::Mat& image, const std::string& caption,
                          ImageEncoding encoding) {
  const bool jpeg = encoding == ImageEncoding::kJpeg;
  if (image.empty() || image.depth() != CV_8U ||
      (image.channels() != 1 && image.channels() != 3 && (image.channels() != 4 || jpeg))) {
    throw std::invalid_argument("report image '" + caption +
                                "' must be a non-empty 8-bit image with 1 or 3 channels (4 for "
                                "PNG)");
  }
  constexpr int kJpegQuality = 85;  // no visible artefacts on rendered frames and overlay text
  std::vector<std::uint8_t> encoded;
  const bool ok =
      jpeg ? cv::imencode(".jpg", image, encoded, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality})
           : cv::imencode(".png", image, encoded);
  if (!ok) {
    throw std::runtime_error(std::string(jpeg ? "JPEG" : "PNG") +
                             " encoding failed for report image '" + caption + "'");
  }
  blocks_.push_back(
      Figure("<img alt=\"" + EscapeXml(caption) + "\" width=\"" + std::to_string(image.cols) +
                 "\" height=\"" + std::to_string(image.rows) + "\" src=\"data:image/" +
                 (jpeg ? "jpeg" : "png") + ";base64," + Base64Encode(encoded) + "\"/>",
             caption));
}

void HtmlReport::AddBlocks(const std::vector<std::string>& blocks) {
  blocks_.insert(blocks_.end(), blocks.begin(), blocks.end());
}

std::string HtmlReport::ToHtml() const {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      EscapeXml(title_) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" +
      EscapeXml(title_) + "</h1>\n";
  html += outcome_html_ + run_html_;
  for (const std::string& block : blocks_) html += block;
  return html + "</body>\n</html>\n";
}

void HtmlReport::Write(const std::string& path) const { WriteFileAtomically(path, ToHtml()); }

}  // namespace aperture::output
