#pragma once
// analysis.png: histograms of a pattern analysis (common/pattern/pattern_analysis.hpp) side by side — spot
// area, neighbour spacing, aspect ratio — so a user sees at a glance whether the spots are of one
// size, evenly spaced and round. Each panel is a step outline of counts over equal-width bins,
// drawn by the line-chart writer (common/output/line_plot.hpp) and pasted into one picture.
#include <string>
#include <vector>

namespace physarum {

struct Histogram {
  std::vector<double> edges;  // bins + 1 increasing edges
  std::vector<int> counts;    // per bin; the last bin includes its upper edge
};

// Equal-width bins over [min, max] of the finite values; Sturges' rule for their number
// (ceil(log2 n) + 1, at most 50). Values that agree to 1e-6 get a range 10 % of their size wide
// around them (1 wide around 0). Empty values give an empty histogram.
Histogram make_histogram(const std::vector<double>& values);

struct HistogramPanel {
  std::string title, x_label;
  std::vector<double> values;
};

// The panels in one row, each 600 x 420 pixels, written atomically. An empty panel says so in its
// title and draws an empty axis. InputError when the file cannot be written.
void write_histograms_png(const std::string& path, const std::vector<HistogramPanel>& panels);

}  // namespace physarum
