// Histograms of a pattern analysis as one PNG.
#include "common/output/pattern_histograms.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "common/output/line_plot.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace physarum {

Histogram make_histogram(const std::vector<double>& values) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  Histogram h;
  if (finite.empty()) return h;
  double lo = *std::min_element(finite.begin(), finite.end()), hi = *std::max_element(finite.begin(), finite.end());
  // Values that (nearly) agree get one readable bin 10 % of their size wide: the chart's axis ticks
  // need a range they can divide.
  if (hi - lo <= 1e-6 * std::max(std::abs(lo), std::abs(hi))) {
    const double half = 0.05 * (std::max(std::abs(lo), std::abs(hi)) > 0.0 ? std::max(std::abs(lo), std::abs(hi)) : 1.0);
    const double middle = 0.5 * (lo + hi);
    lo = middle - half;
    hi = middle + half;
  }
  const int bins = std::min(50, static_cast<int>(std::ceil(std::log2(static_cast<double>(finite.size())))) + 1);
  h.counts.assign(static_cast<size_t>(bins), 0);
  for (int i = 0; i <= bins; ++i) h.edges.push_back(lo + (hi - lo) * i / bins);
  for (double v : finite) {
    const int bin = std::clamp(static_cast<int>((v - lo) / (hi - lo) * bins), 0, bins - 1);
    ++h.counts[static_cast<size_t>(bin)];
  }
  return h;
}

void write_histograms_png(const std::string& path, const std::vector<HistogramPanel>& panels) {
  constexpr int kPanelWidth = 600, kPanelHeight = 420;
  write_file_atomically(path, [&](const std::string& temporary) {
    OIIO::ImageBuf row(OIIO::ImageSpec(kPanelWidth * static_cast<int>(panels.size()), kPanelHeight, 3, OIIO::TypeDesc::FLOAT));
    for (size_t p = 0; p < panels.size(); ++p) {
      const HistogramPanel& panel = panels[p];
      const Histogram h = make_histogram(panel.values);
      PlotSeries outline;
      double mean = 0.0;
      int finite = 0;
      for (double v : panel.values)
        if (std::isfinite(v)) mean += v, ++finite;
      char label[96];
      std::snprintf(label, sizeof label, "%d values, mean %.4g", finite, finite > 0 ? mean / finite : 0.0);
      outline.label = label;
      outline.color = {0.12f, 0.35f, 0.65f};
      std::string title = panel.title;
      if (h.counts.empty()) {
        outline.x = {0.0, 1.0};
        outline.y = {0.0, 0.0};
        title += " (none)";
      } else {
        outline.x.push_back(h.edges.front());
        outline.y.push_back(0.0);
        for (size_t b = 0; b < h.counts.size(); ++b) {
          outline.x.insert(outline.x.end(), {h.edges[b], h.edges[b + 1]});
          outline.y.insert(outline.y.end(), {static_cast<double>(h.counts[b]), static_cast<double>(h.counts[b])});
        }
        outline.x.push_back(h.edges.back());
        outline.y.push_back(0.0);
      }
      PlotOptions options;
      options.width = kPanelWidth;
      options.height = kPanelHeight;
      options.title = title;
      options.x_label = panel.x_label;
      options.y_label = "count";
      // The panel goes through the chart writer's own file, read back and pasted into the row.
      const std::string panel_path = temporary + ".panel" + std::to_string(p) + ".png";
      try {
        write_line_plot_png(panel_path, {outline}, options);
        OIIO::ImageBuf image(panel_path);
        if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT) ||
            !OIIO::ImageBufAlgo::paste(row, kPanelWidth * static_cast<int>(p), 0, 0, 0, image))
          throw InputError(path + ": cannot compose the histogram panels: " + image.geterror() + row.geterror());
      } catch (...) {
        std::filesystem::remove(panel_path);
        throw;
      }
      std::filesystem::remove(panel_path);
    }
    if (!row.write(temporary, OIIO::TypeDesc::UINT8, "png")) throw InputError(path + ": cannot write PNG: " + row.geterror());
  });
}

}  // namespace physarum
