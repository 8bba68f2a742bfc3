#pragma once
// Small line charts written as PNG through OpenImageIO (lines, markers, error bars, axes with
// ticks, title and legend; text in DejaVu Sans when the font is installed): the spectra plot of the
// differential harness and the scaling plots of the benchmarks. Linear or logarithmic axes.
#include <array>
#include <string>
#include <vector>

namespace physarum {

struct PlotSeries {
  std::string label;
  std::array<float, 3> color{0.0f, 0.0f, 0.0f};  // RGB in [0, 1]
  std::vector<double> x, y;
  // Optional error bars: y_low[i] .. y_high[i] (both empty, or the size of y).
  std::vector<double> y_low, y_high;
  bool dashed = false;
};

struct PlotOptions {
  int width = 900, height = 560;
  bool log_x = false, log_y = false;
  std::string title, x_label, y_label;
};

// Writes the chart (atomically: temporary name, then rename). Points that cannot be drawn (not
// finite, or <= 0 on a log axis) are skipped. Throws InputError when nothing at all can be drawn or
// the file cannot be written.
void write_line_plot_png(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace physarum
