#pragma once
// HtmlReport: one self-contained report.html (inline CSS, inline SVG, images as base64 PNG or
// JPEG data URIs) that opens offline in any browser. Blocks appear in the order they are added.
//
//   HtmlReport report("aperture run: gap sequence");
//   report.AddOutcome({"done", "120 frames, gap in 118", {{"gap detected", "98 %", ""}}});
//   report.AddRunDescription(out.summary(), out.ElapsedSeconds());
//   report.AddSvg(plot.Render(), "Position error over time");
//   report.AddImage(key_frame, "Frame 120 with detected gap");
//   report.AddCollapsedTable(out.summary(), "Every figure of summary.json");  // last
//   report.Write(out.Path("report.html"));          // atomic
//
// A reader sees the outcome first, then what was run, then the details; the full key/value
// table comes last, folded.
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace aperture::output {

// One headline figure of a run against its target ("" when it has none).
struct ReportFigure {
  std::string name;
  std::string value;
  std::string target;
};

struct ReportOutcome {
  std::string verdict;   // "passed" | "failed" | "done" (a run without a pass criterion)
  std::string headline;  // one sentence
  std::vector<ReportFigure> figures;
};

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  // The outcome box (styled by verdict). It opens the page whenever it is added (the outcome is
  // known last); a second call replaces it.
  void AddOutcome(const ReportOutcome& outcome);
  // "What was run", shown right under the outcome: summary["command"] and summary["inputs"], the
  // wall time and the effective configuration summary["config"] (folded).
  void AddRunDescription(const nlohmann::json& summary, double wall_time_s);

  void AddSection(const std::string& heading);
  void AddParagraph(const std::string& text);  // plain text, escaped
  // An object becomes a key/value table (nested objects flatten to dotted keys); an array of
  // objects becomes a table with one row per element and the union of keys as columns. Anything
  // else is shown as JSON text. Numbers print with up to 6 significant digits.
  void AddTable(const nlohmann::json& data, const std::string& caption = "");
  // AddTable folded in a <details> block that opens on a click on `label`.
  void AddCollapsedTable(const nlohmann::json& data, const std::string& label);
  // `svg` is inserted verbatim (trusted: produced by SvgPlot).
  void AddSvg(const std::string& svg, const std::string& caption = "");
  // kPng: lossless (for images read back or measured); kJpeg: quality 85, ~10x smaller on
  // rendered frames (for video key frames; 4-channel images are not JPEG-encoded: use kPng).
  enum class ImageEncoding { kPng, kJpeg };
  // Encodes `image` (8-bit 1/3/4 channels, BGR order as elsewhere in OpenCV) and embeds it.
  // std::invalid_argument naming `caption` for an empty image or an unsupported type.
  void AddImage(const cv::Mat& image, const std::string& caption = "",
                ImageEncoding encoding = ImageEncoding::kPng);

  // The blocks added so far (sections, paragraphs, tables, figures; not the outcome and run
  // description), and blocks of another report appended verbatim (trusted: e.g. a bench section
  // recorded in a shard of the run, experiments/bench/section_record.h).
  const std::vector<std::string>& blocks() const { return blocks_; }
  void AddBlocks(const std::vector<std::string>& blocks);

  std::string ToHtml() const;
  // Writes ToHtml() atomically to `path`.
  void Write(const std::string& path) const;

 private:
  std::string title_;
  std::string outcome_html_, run_html_;  // the head of the page, in this order
  std::vector<std::string> blocks_;      // HTML fragments
};

}  // namespace aperture::output
