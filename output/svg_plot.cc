#include "output/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace aperture::output {
namespace {

// Matplotlib's tab10: distinguishable, colour-blind friendly enough for up to 10 series.
constexpr const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

const char* Colour(std::size_t index) { return kPalette[index % kPaletteSize]; }

// Pixel coordinates with two decimals: sub-pixel precise, compact.
std::string Px(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", value);
  return buffer;
}

std::string TickLabel(double value, double step) {
  char buffer[48];
  // Enough digits to tell neighbouring ticks apart (2.5 x 10^k steps need one more).
  const double step_exponent = std::floor(std::log10(step) + 1e-9);
  const bool two_and_a_half = std::abs(step / std::pow(10.0, step_exponent) - 2.5) < 1e-9;
  const int extra = two_and_a_half ? 1 : 0;
  const double magnitude = std::max(std::abs(value), std::abs(step));
  if (magnitude >= 1e6 || step < 1e-4) {
    // Exponent notation with as many significant digits as the step resolves (e.g. 1.70000001e+09).
    const int digits =
        static_cast<int>(std::floor(std::log10(magnitude) + 1e-9) - step_exponent) + 1 + extra;
    std::snprintf(buffer, sizeof(buffer), "%.*g", std::clamp(digits, 1, 17), value);
  } else {
    const int decimals = std::max(0, static_cast<int>(-step_exponent) + extra);
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value == 0.0 ? 0.0 : value);
  }
  return buffer;
}

struct Range {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  void Add(double value) {
    if (!std::isfinite(value)) return;
    min = std::min(min, value);
    max = std::max(max, value);
  }
};

// Plot frame: margins, axes, ticks, grid, labels, title and legend around a data rectangle.
class Canvas {
 public:
  Canvas(const SvgPlotOptions& options, const AxisTicks& x_ticks, const AxisTicks& y_ticks)
      : options_(options), x_ticks_(x_ticks), y_ticks_(y_ticks) {
    left_ = 64.0;
    right_ = options.width_px - 16.0;
    top_ = options.title.empty() ? 16.0 : 36.0;
    bottom_ = options.height_px - (options.x_label.empty() ? 28.0 : 46.0);
  }

  double X(double value) const {
    return left_ + (value - x_ticks_.min()) / (x_ticks_.max() - x_ticks_.min()) * (right_ - left_);
  }
  double Y(double value) const {
    return bottom_ -
           (value - y_ticks_.min()) / (y_ticks_.max() - y_ticks_.min()) * (bottom_ - top_);
  }
  double left() const { return left_; }
  double right() const { return right_; }
  double bottom() const { return bottom_; }

  // Opening tag, background, title, axis labels, y grid + ticks, and x ticks unless the caller
  // draws categorical labels itself.
  void Begin(std::ostringstream& svg, bool numeric_x_ticks) const {
    const int width = options_.width_px, height = options_.height_px;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" viewBox=\"0 0 " << width << ' ' << height
        << "\" font-family=\"sans-serif\" font-size=\"11\" class=\"plot\">\n"
        << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
        << "\" fill=\"white\"/>\n";
    if (!options_.title.empty()) {
      svg << "<text x=\"" << Px((left_ + right_) / 2) << "\" y=\"22\" text-anchor=\"middle\" "
          << "font-size=\"14\" font-weight=\"bold\">" << EscapeXml(options_.title) << "</text>\n";
    }
    svg << "<g class=\"y-ticks\" stroke=\"#e0e0e0\">\n";
    for (const double tick : y_ticks_.values) {
      svg << "<line x1=\"" << Px(left_) << "\" y1=\"" << Px(Y(tick)) << "\" x2=\"" << Px(right_)
          << "\" y2=\"" << Px(Y(tick)) << "\"/>\n";
    }
    svg << "</g>\n<g class=\"y-tick-labels\" text-anchor=\"end\">\n";
    for (const double tick : y_ticks_.values) {
      svg << "<text x=\"" << Px(left_ - 5) << "\" y=\"" << Px(Y(tick) + 4) << "\">"
          << TickLabel(tick, y_ticks_.step) << "</text>\n";
    }
    svg << "</g>\n";
    if (numeric_x_ticks) {
      svg << "<g class=\"x-tick-labels\" text-anchor=\"middle\">\n";
      for (const double tick : x_ticks_.values) {
        svg << "<line x1=\"" << Px(X(tick)) << "\" y1=\"" << Px(bottom_) << "\" x2=\""
            << Px(X(tick)) << "\" y2=\"" << Px(bottom_ + 4) << "\" stroke=\"black\"/>"
            << "<text x=\"" << Px(X(tick)) << "\" y=\"" << Px(bottom_ + 16) << "\">"
            << TickLabel(tick, x_ticks_.step) << "</text>\n";
      }
      svg << "</g>\n";
    }
    svg << "<rect x=\"" << Px(left_) << "\" y=\"" << Px(top_) << "\" width=\"" << Px(right_ - left_)
        << "\" height=\"" << Px(bottom_ - top_) << "\" fill=\"none\" stroke=\"black\"/>\n";
    if (!options_.x_label.empty()) {
      svg << "<text x=\"" << Px((left_ + right_) / 2) << "\" y=\"" << Px(height - 8.0)
          << "\" text-anchor=\"middle\">" << EscapeXml(options_.x_label) << "</text>\n";
    }
    if (!options_.y_label.empty()) {
      svg << "<text transform=\"translate(14," << Px((top_ + bottom_) / 2)
          << ") rotate(-90)\" text-anchor=\"middle\">" << EscapeXml(options_.y_label)
          << "</text>\n";
    }
  }

  void Legend(std::ostringstream& svg, const std::vector<std::string>& names) const {
    if (names.empty()) return;
    std::size_t longest = 0;
    for (const std::string& name : names) longest = std::max(longest, name.size());
    const double width = 28.0 + 6.5 * static_cast<double>(longest);
    const double x = right_ - width - 6, y = top_ + 6;
    svg << "<g class=\"legend\">\n<rect x=\"" << Px(x) << "\" y=\"" << Px(y) << "\" width=\""
        << Px(width) << "\" height=\"" << Px(16.0 * names.size() + 4)
        << "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#999\"/>\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
      const double row = y + 12 + 16.0 * i;
      svg << "<rect x=\"" << Px(x + 5) << "\" y=\"" << Px(row - 7)
          << "\" width=\"14\" height=\"8\" "
          << "fill=\"" << Colour(i) << "\"/><text x=\"" << Px(x + 23) << "\" y=\"" << Px(row)
          << "\">" << EscapeXml(names[i]) << "</text>\n";
    }
    svg << "</g>\n";
  }

 private:
  const SvgPlotOptions& options_;
  AxisTicks x_ticks_, y_ticks_;
  double left_, right_, top_, bottom_;
};

void CheckOptions(const SvgPlotOptions& options) {
  if (options.width_px < 160 || options.height_px < 120) {
    throw std::invalid_argument(
        "plot '" + options.title + "' is " + std::to_string(options.width_px) + "x" +
        std::to_string(options.height_px) + " px; use at least 160x120 to leave room for the axes");
  }
}

}  // namespace

std::string EscapeXml(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&#39;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

AxisTicks ComputeNiceTicks(double data_min, double data_max, int target_tick_count) {
  if (!std::isfinite(data_min) || !std::isfinite(data_max)) {
    data_min = 0.0;
    data_max = 1.0;
  }
  if (data_max < data_min) std::swap(data_min, data_max);
  if (data_max - data_min <= 1e-12 * std::max(1.0, std::abs(data_min))) {
    const double pad = data_min == 0.0 ? 1.0 : 0.1 * std::abs(data_min);
    data_min -= pad;
    data_max += pad;
  }
  const double raw_step = (data_max - data_min) / std::max(1, target_tick_count - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw_step)));
  const double residual = raw_step / magnitude;
  const double nice = residual <= 1.0   ? 1.0
                      : residual <= 2.0 ? 2.0
                      : residual <= 2.5 ? 2.5
                      : residual <= 5.0 ? 5.0
                                        : 10.0;
  AxisTicks ticks;
  ticks.step = nice * magnitude;
  // The small tolerance keeps a bound that is already a tick value from adding an extra tick.
  double first = std::floor(data_min / ticks.step + 1e-9);
  double last = std::ceil(data_max / ticks.step - 1e-9);
  // ...but the ticks must still cover the data after rounding of k * step.
  if (first * ticks.step > data_min) first -= 1.0;
  if (last * ticks.step < data_max) last += 1.0;
  for (double k = first; k <= last + 0.5; k += 1.0) {
    const double value = k * ticks.step;
    ticks.values.push_back(std::abs(value) < 1e-9 * ticks.step ? 0.0 : value);
  }
  return ticks;
}

BoxStats ComputeBoxStats(const std::vector<double>& values) {
  std::vector<double> sorted;
  for (const double v : values) {
    if (std::isfinite(v)) sorted.push_back(v);
  }
  std::sort(sorted.begin(), sorted.end());
  BoxStats stats;
  stats.count = sorted.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (sorted.empty()) {
    stats.q1 = stats.median = stats.q3 = stats.whisker_low = stats.whisker_high = nan;
    return stats;
  }
  const auto quantile = [&sorted](double p) {
    const double position = p * static_cast<double>(sorted.size() - 1);
    const std::size_t below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double fraction = position - static_cast<double>(below);
    return sorted[below] + fraction * (sorted[above] - sorted[below]);
  };
  stats.q1 = quantile(0.25);
  stats.median = quantile(0.5);
  stats.q3 = quantile(0.75);
  const double iqr = stats.q3 - stats.q1;
  const double low_fence = stats.q1 - 1.5 * iqr, high_fence = stats.q3 + 1.5 * iqr;
  stats.whisker_low = stats.q1;
  stats.whisker_high = stats.q3;
  for (const double v : sorted) {
    if (v < low_fence || v > high_fence) {
      stats.outliers.push_back(v);
    } else {
      stats.whisker_low = std::min(stats.whisker_low, v);
      stats.whisker_high = std::max(stats.whisker_high, v);
    }
  }
  return stats;
}

SvgPlot::SvgPlot(SvgPlotOptions options) : options_(std::move(options)) { CheckOptions(options_); }

SvgPlot& SvgPlot::AddLine(const std::string& name, const std::vector<double>& x,
                          const std::vector<double>& y) {
  return Add(name, x, y, true);
}

SvgPlot& SvgPlot::AddScatter(const std::string& name, const std::vector<double>& x,
                             const std::vector<double>& y) {
  return Add(name, x, y, false);
}

SvgPlot& SvgPlot::Add(const std::string& name, const std::vector<double>& x,
                      const std::vector<double>& y, bool line) {
  if (x.size() != y.size()) {
    throw std::invalid_argument("plot '" + options_.title + "', series '" + name +
                                "': " + std::to_string(x.size()) + " x values but " +
                                std::to_string(y.size()) + " y values; they must pair up");
  }
  series_.push_back(Series{name, x, y, line});
  return *this;
}

std::string SvgPlot::Render() const {
  Range x_range, y_range;
  for (const Series& series : series_) {
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
      x_range.Add(series.x[i]);
      y_range.Add(series.y[i]);
    }
  }
  const Canvas canvas(options_, ComputeNiceTicks(x_range.min, x_range.max),
                      ComputeNiceTicks(y_range.min, y_range.max));
  std::ostringstream svg;
  canvas.Begin(svg, true);
  std::vector<std::string> names;
  for (std::size_t s = 0; s < series_.size(); ++s) {
    const Series& series = series_[s];
    names.push_back(series.name);
    const std::string name = EscapeXml(series.name);
    if (series.line) {
      // One polyline per run of finite samples: a gap in the data stays a gap in the plot.
      std::string points;
      const auto flush = [&] {
        if (points.empty()) return;
        svg << "<polyline class=\"series\" data-series=\"" << name << "\" fill=\"none\" stroke=\""
            << Colour(s) << "\" stroke-width=\"1.5\" points=\"" << points << "\"/>\n";
        points.clear();
      };
      for (std::size_t i = 0; i < series.x.size(); ++i) {
        if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) {
          flush();
          continue;
        }
        points += (points.empty() ? "" : " ") + Px(canvas.X(series.x[i])) + "," +
                  Px(canvas.Y(series.y[i]));
      }
      flush();
    } else {
      svg << "<g class=\"series\" data-series=\"" << name << "\" fill=\"" << Colour(s) << "\">\n";
      for (std::size_t i = 0; i < series.x.size(); ++i) {
        if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
        svg << "<circle cx=\"" << Px(canvas.X(series.x[i])) << "\" cy=\""
            << Px(canvas.Y(series.y[i])) << "\" r=\"2.5\"/>\n";
      }
      svg << "</g>\n";
    }
  }
  canvas.Legend(svg, names);
  svg << "</svg>\n";
  return svg.str();
}

std::string SvgPlot::Histogram(const SvgPlotOptions& options,
                               const std::vector<NamedValues>& series, int bin_count) {
  CheckOptions(options);
  Range range;
  std::size_t largest = 0;
  for (const NamedValues& s : series) {
    std::size_t finite = 0;
    for (const double v : s.values) {
      range.Add(v);
      finite += std::isfinite(v) ? 1 : 0;
    }
    largest = std::max(largest, finite);
  }
  if (bin_count <= 0) {
    // Sturges' rule: adequate for the roughly unimodal error distributions plotted here.
    bin_count =
        largest == 0 ? 1 : static_cast<int>(std::ceil(std::log2(static_cast<double>(largest)))) + 1;
  }
  const AxisTicks x_ticks = ComputeNiceTicks(range.min, range.max);
  double low = range.min, high = range.max;
  if (!(high > low)) {  // empty or constant data: one bin around the value
    low = x_ticks.min();
    high = x_ticks.max();
  }
  const double width = (high - low) / bin_count;
  std::vector<std::vector<int>> counts(series.size(), std::vector<int>(bin_count, 0));
  int max_count = 0;
  for (std::size_t s = 0; s < series.size(); ++s) {
    for (const double v : series[s].values) {
      if (!std::isfinite(v)) continue;
      // The last bin is closed so the maximum is counted.
      const int bin = std::min(bin_count - 1, static_cast<int>((v - low) / width));
      max_count = std::max(max_count, ++counts[s][bin]);
    }
  }
  const Canvas canvas(options, x_ticks, ComputeNiceTicks(0.0, std::max(1, max_count)));
  std::ostringstream svg;
  canvas.Begin(svg, true);
  std::vector<std::string> names;
  for (std::size_t s = 0; s < series.size(); ++s) {
    names.push_back(series[s].name);
    svg << "<g class=\"series\" data-series=\"" << EscapeXml(series[s].name) << "\" fill=\""
        << Colour(s) << "\" fill-opacity=\"" << (series.size() > 1 ? "0.5" : "0.8") << "\">\n";
    for (int b = 0; b < bin_count; ++b) {
      if (counts[s][b] == 0) continue;
      const double x0 = canvas.X(low + b * width), x1 = canvas.X(low + (b + 1) * width);
      const double y = canvas.Y(counts[s][b]);
      svg << "<rect class=\"bin\" data-count=\"" << counts[s][b] << "\" x=\"" << Px(x0) << "\" y=\""
          << Px(y) << "\" width=\"" << Px(x1 - x0) << "\" height=\"" << Px(canvas.bottom() - y)
          << "\"/>\n";
    }
    svg << "</g>\n";
  }
  if (series.size() > 1) canvas.Legend(svg, names);
  svg << "</svg>\n";
  return svg.str();
}

std::string SvgPlot::BoxPlot(const SvgPlotOptions& options,
                             const std::vector<NamedValues>& groups) {
  CheckOptions(options);
  Range range;
  for (const NamedValues& group : groups) {
    for (const double v : group.values) range.Add(v);
  }
  // Categories sit at 0..n-1; the x axis spans [-0.5, n-0.5].
  AxisTicks x_axis;
  x_axis.values = {-0.5, std::max<double>(groups.size(), 1) - 0.5};
  const Canvas canvas(options, x_axis, ComputeNiceTicks(range.min, range.max));
  std::ostringstream svg;
  canvas.Begin(svg, false);
  const double half_width =
      0.3 * (canvas.right() - canvas.left()) / std::max<double>(groups.size(), 1);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const double center = canvas.X(static_cast<double>(g));
    svg << "<text class=\"category\" x=\"" << Px(center) << "\" y=\"" << Px(canvas.bottom() + 16)
        << "\" text-anchor=\"middle\">" << EscapeXml(groups[g].name) << "</text>\n";
    const BoxStats stats = ComputeBoxStats(groups[g].values);
    if (stats.count == 0) continue;
    const std::string left = Px(center - half_width), right = Px(center + half_width);
    svg << "<g class=\"box\" data-series=\"" << EscapeXml(groups[g].name) << "\" stroke=\""
        << Colour(g) << "\" stroke-width=\"1.5\">\n"
        << "<line x1=\"" << Px(center) << "\" y1=\"" << Px(canvas.Y(stats.whisker_low))
        << "\" x2=\"" << Px(center) << "\" y2=\"" << Px(canvas.Y(stats.q1)) << "\"/>\n"
        << "<line x1=\"" << Px(center) << "\" y1=\"" << Px(canvas.Y(stats.q3)) << "\" x2=\""
        << Px(center) << "\" y2=\"" << Px(canvas.Y(stats.whisker_high)) << "\"/>\n"
        << "<rect x=\"" << left << "\" y=\"" << Px(canvas.Y(stats.q3)) << "\" width=\""
        << Px(2 * half_width) << "\" height=\"" << Px(canvas.Y(stats.q1) - canvas.Y(stats.q3))
        << "\" fill=\"" << Colour(g) << "\" fill-opacity=\"0.25\"/>\n"
        << "<line class=\"median\" x1=\"" << left << "\" y1=\"" << Px(canvas.Y(stats.median))
        << "\" x2=\"" << right << "\" y2=\"" << Px(canvas.Y(stats.median))
        << "\" stroke-width=\"2.5\"/>\n";
    for (const double whisker : {stats.whisker_low, stats.whisker_high}) {
      svg << "<line x1=\"" << Px(center - half_width / 2) << "\" y1=\"" << Px(canvas.Y(whisker))
          << "\" x2=\"" << Px(center + half_width / 2) << "\" y2=\"" << Px(canvas.Y(whisker))
          << "\"/>\n";
    }
    for (const double outlier : stats.outliers) {
      svg << "<circle class=\"outlier\" cx=\"" << Px(center) << "\" cy=\"" << Px(canvas.Y(outlier))
          << "\" r=\"2.5\" fill=\"none\"/>\n";
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace aperture::output
