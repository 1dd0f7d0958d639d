#pragma once
// SvgPlot: small self-contained SVG charts for report.html (no JavaScript, no external files).
//
//   SvgPlot plot({"Position error", "t [s]", "error [m]"});
//   plot.AddLine("x", t_s, error_x_m).AddLine("y", t_s, error_y_m).AddScatter("fix", t_fix, e_fix);
//   report.AddSvg(plot.Render());
//   report.AddSvg(SvgPlot::Histogram({"Reprojection error", "px", "count"}, {{"all", errors}}));
//   report.AddSvg(SvgPlot::BoxPlot({"Latency per node", "", "ms"}, {{"gap", a}, {"led", b}}));
//
// Axes get "nice" ticks (1, 2, 2.5, 5 x 10^k) that cover the data range. Non-finite values are
// skipped (a line is broken at them, never drawn through them); empty series and empty plots
// render axes only. Each line series is one or more <polyline class="series"> elements carrying
// data-series="<name>", with one point per finite sample.
#include <string>
#include <utility>
#include <vector>

namespace aperture::output {

struct SvgPlotOptions {
  // Implicit from a title so SvgPlot({"Error", "t [s]", "e [m]"}) reads naturally.
  SvgPlotOptions(std::string title_text = "", std::string x_label_text = "",
                 std::string y_label_text = "")
      : title(std::move(title_text)),
        x_label(std::move(x_label_text)),
        y_label(std::move(y_label_text)) {}

  std::string title;
  std::string x_label;
  std::string y_label;
  int width_px = 640;  // viewBox size; the page scales it to the column width
  int height_px = 360;
};

struct NamedValues {
  std::string name;
  std::vector<double> values;
};

// Evenly spaced round tick values with first <= data_min and last >= data_max.
struct AxisTicks {
  std::vector<double> values;
  double step = 1.0;
  double min() const { return values.front(); }
  double max() const { return values.back(); }
};
// Non-finite bounds fall back to [0, 1]; a zero-width range is widened around its value.
AxisTicks ComputeNiceTicks(double data_min, double data_max, int target_tick_count = 6);

// Tukey box-plot statistics of the finite values (quartiles by linear interpolation between order
// statistics; whiskers at the most extreme values within 1.5 IQR of the box).
struct BoxStats {
  std::size_t count = 0;  // finite values; everything below is NaN when 0
  double q1, median, q3, whisker_low, whisker_high;
  std::vector<double> outliers;
};
BoxStats ComputeBoxStats(const std::vector<double>& values);

class SvgPlot {
 public:
  explicit SvgPlot(SvgPlotOptions options);

  // x and y must have the same length (std::invalid_argument naming the series otherwise).
  SvgPlot& AddLine(const std::string& name, const std::vector<double>& x,
                   const std::vector<double>& y);
  SvgPlot& AddScatter(const std::string& name, const std::vector<double>& x,
                      const std::vector<double>& y);
  std::string Render() const;

  // Counts per bin; all series share the bins. bin_count 0 = Sturges' rule on the largest series.
  static std::string Histogram(const SvgPlotOptions& options,
                               const std::vector<NamedValues>& series, int bin_count = 0);
  // One box per group, groups side by side in the given order.
  static std::string BoxPlot(const SvgPlotOptions& options, const std::vector<NamedValues>& groups);

 private:
  struct Series {
    std::string name;
    std::vector<double> x, y;
    bool line;
  };
  SvgPlot& Add(const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
               bool line);

  SvgPlotOptions options_;
  std::vector<Series> series_;
};

// Escapes &, <, >, " and ' for SVG/HTML text and attributes.
std::string EscapeXml(const std::string& text);

}  // namespace aperture::output
