#include "api/compare/comparison_plot.hpp"

#include "common/harness/equivalence_test.hpp"
#include "common/output/line_plot.hpp"

#include <cmath>

namespace physarum {

bool write_comparison_plot(const std::string& path, const std::vector<std::string>& metric_names,
                           const std::vector<std::vector<double>>& reference,
                           const std::vector<std::vector<double>>& opencl) {
  std::vector<PlotSeries> series;
  for (const auto& [prefix, dashed] : {std::pair<std::string, bool>{"harmonic_band_", false}, {"radial_band_", true}}) {
    struct Arm {
      const char* name;
      const std::vector<std::vector<double>>* rows;
      std::array<float, 3> color;
    };
    for (const Arm& arm : {Arm{"reference", &reference, {0.12f, 0.35f, 0.75f}}, Arm{"opencl", &opencl, {0.85f, 0.35f, 0.1f}}}) {
      const char* name = arm.name;
      const std::vector<std::vector<double>>* rows = arm.rows;
      const std::array<float, 3> color = arm.color;
      PlotSeries s;
      s.label = std::string(name) + (dashed ? " (radial FFT)" : " (harmonics)");
      s.color = color;
      s.dashed = dashed;
      int band = 0;
      for (size_t j = 0; j < metric_names.size(); ++j) {
        if (metric_names[j].rfind(prefix, 0) != 0) continue;
        std::vector<double> values;
        for (const auto& row : *rows) values.push_back(row[j]);
        const SampleSummary m = summarize_samples(values);
        s.x.push_back(++band + (dashed ? 0.1 : 0.0) + (rows == &opencl ? 0.05 : 0.0));
        s.y.push_back(m.mean);
        s.y_low.push_back(m.mean - m.sd);
        s.y_high.push_back(m.mean + m.sd);
      }
      if (!s.x.empty()) series.push_back(std::move(s));
    }
  }
  bool drawable = false;
  for (const PlotSeries& s : series)
    for (double y : s.y) drawable = drawable || (std::isfinite(y) && y > 0.0);
  if (!drawable) return false;
  PlotOptions options;
  options.log_y = true;
  options.title = "Spectral band powers, mean +- 1 sd over seeds";
  options.x_label = "band (low to high spatial frequency)";
  options.y_label = "power / mean^2";
  write_line_plot_png(path, series, options);
  return true;
}

}  // namespace physarum
