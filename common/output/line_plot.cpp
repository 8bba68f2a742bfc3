#include "common/output/line_plot.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace physarum {
namespace {

constexpr const char* kFont = "DejaVuSans";
constexpr int kLeft = 90, kRight = 30, kTop = 50, kBottom = 70;  // margins around the plot area

// One axis: data range, log or linear, mapped onto a pixel interval.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in transformed units (log10 for log axes)
  double pixel_from = 0.0, pixel_to = 1.0;

  bool drawable(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double transform(double v) const { return log ? std::log10(v) : v; }
  double pixel(double v) const { return pixel_from + (transform(v) - lo) / (hi - lo) * (pixel_to - pixel_from); }

  void fit(const std::vector<double>& values) {
    double a = std::numeric_limits<double>::infinity(), b = -a;
    for (double v : values)
      if (drawable(v)) a = std::min(a, transform(v)), b = std::max(b, transform(v));
    if (!(a <= b)) return;
    if (log) {
      lo = std::floor(a);
      hi = std::ceil(b);
      if (hi - lo < 1.0) hi = lo + 1.0;
    } else {
      const double pad = b > a ? 0.05 * (b - a) : (a != 0.0 ? 0.1 * std::abs(a) : 1.0);
      lo = a - pad;
      hi = b + pad;
    }
  }

  // Tick values in data units: powers of ten (log), or 1-2-5 steps (linear).
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log) {
      for (double e = lo; e <= hi + 1e-9; e += 1.0) t.push_back(std::pow(10.0, e));
      return t;
    }
    const double raw = (hi - lo) / 6.0;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * magnitude >= raw) {
        step = m * magnitude;
        break;
      }
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
    return t;
  }
};

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void text(OIIO::ImageBuf& image, int x, int y, const std::string& s, int size, OIIO::ImageBufAlgo::TextAlignX ax,
          OIIO::ImageBufAlgo::TextAlignY ay) {
  const float black[3] = {0.1f, 0.1f, 0.1f};
  // Without the font (fonts-dejavu-core) the chart is still drawn, unlabelled.
  OIIO::ImageBufAlgo::render_text(image, x, y, s, size, kFont, black, ax, ay);
}

using AX = OIIO::ImageBufAlgo::TextAlignX;
using AY = OIIO::ImageBufAlgo::TextAlignY;
constexpr float kWhite[3] = {1.0f, 1.0f, 1.0f}, kGrid[3] = {0.88f, 0.88f, 0.88f}, kAxis[3] = {0.2f, 0.2f, 0.2f};

// The axes fitted to every drawable point (error bars included) and placed inside the margins.
void fit_axes(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options, Axis& ax,
              Axis& ay) {
  const int w = options.width, h = options.height;
  std::vector<double> xs, ys;
  for (const PlotSeries& s : series) {
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!ax.drawable(s.x[i]) || !ay.drawable(s.y[i])) continue;
      xs.push_back(s.x[i]);
      ys.push_back(s.y[i]);
      if (i < s.y_low.size() && ay.drawable(s.y_low[i])) ys.push_back(s.y_low[i]);
      if (i < s.y_high.size() && ay.drawable(s.y_high[i])) ys.push_back(s.y_high[i]);
    }
  }
  if (xs.empty()) throw InputError(path + ": nothing to plot (no finite point" + (options.log_y ? " > 0" : "") + ")");
  ax.fit(xs);
  ay.fit(ys);
  ax.pixel_from = kLeft, ax.pixel_to = w - kRight;
  ay.pixel_from = h - kBottom, ay.pixel_to = kTop;
}

void draw_grid_and_ticks(OIIO::ImageBuf& image, const Axis& ax, const Axis& ay, int w, int h) {
  for (double t : ax.ticks()) {
    const int px = static_cast<int>(std::lround(ax.pixel(t)));
    OIIO::ImageBufAlgo::render_line(image, px, kTop, px, h - kBottom, kGrid);
    text(image, px, h - kBottom + 20, tick_label(t), 14, AX::Center, AY::Baseline);
  }
  for (double t : ay.ticks()) {
    const int py = static_cast<int>(std::lround(ay.pixel(t)));
    OIIO::ImageBufAlgo::render_line(image, kLeft, py, w - kRight, py, kGrid);
    text(image, kLeft - 6, py + 5, tick_label(t), 14, AX::Right, AY::Baseline);
  }
  OIIO::ImageBufAlgo::render_box(image, kLeft, kTop, w - kRight, h - kBottom, kAxis);
}

// The line from the previous point to this one, solid or dashed.
void draw_segment(OIIO::ImageBuf& image, const PlotSeries& s, int previous_x, int previous_y, int px, int py) {
  const OIIO::cspan<float> c(s.color.data(), 3);
  // Dashed: 10-pixel dashes with 6-pixel gaps along the segment.
  const double length = std::hypot(px - previous_x, py - previous_y);
  const double dash = s.dashed ? 10.0 : length, period = s.dashed ? 16.0 : length + 1.0;
  for (double from = 0.0; from < length; from += period) {
    const double to = std::min(length, from + dash);
    const auto at = [&](double u, int a, int b) { return static_cast<int>(std::lround(a + (b - a) * u / length)); };
    const int x0 = at(from, previous_x, px), y0 = at(from, previous_y, py);
    const int x1 = at(to, previous_x, px), y1 = at(to, previous_y, py);
    OIIO::ImageBufAlgo::render_line(image, x0, y0, x1, y1, c);
    OIIO::ImageBufAlgo::render_line(image, x0, y0 + 1, x1, y1 + 1, c);
  }
}

// One series: at each point its error bar, then the line from the previous point, then its marker.
void draw_series(OIIO::ImageBuf& image, const PlotSeries& s, const Axis& ax, const Axis& ay) {
  const OIIO::cspan<float> c(s.color.data(), 3);
  int previous_x = 0, previous_y = 0;
  bool have_previous = false;
  for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    if (!ax.drawable(s.x[i]) || !ay.drawable(s.y[i])) {
      have_previous = false;
      continue;
    }
    const int px = static_cast<int>(std::lround(ax.pixel(s.x[i])));
    const int py = static_cast<int>(std::lround(ay.pixel(s.y[i])));
    if (i < s.y_low.size() && i < s.y_high.size() && ay.drawable(s.y_low[i]) && ay.drawable(s.y_high[i])) {
      const int lo = static_cast<int>(std::lround(ay.pixel(s.y_low[i])));
      const int hi = static_cast<int>(std::lround(ay.pixel(s.y_high[i])));
      OIIO::ImageBufAlgo::render_line(image, px, lo, px, hi, c);
      OIIO::ImageBufAlgo::render_line(image, px - 4, lo, px + 4, lo, c);
      OIIO::ImageBufAlgo::render_line(image, px - 4, hi, px + 4, hi, c);
    }
    if (have_previous) draw_segment(image, s, previous_x, previous_y, px, py);
    OIIO::ImageBufAlgo::render_box(image, px - 3, py - 3, px + 3, py + 3, c, true);
    previous_x = px, previous_y = py, have_previous = true;
  }
}

// The legend (inside the plot area, on white, in whichever top or bottom corner covers the fewest
// points).
void draw_legend(OIIO::ImageBuf& image, const std::vector<PlotSeries>& series, const Axis& ax, const Axis& ay, int w,
                 int h) {
  int legend_width = 0;
  for (const PlotSeries& s : series) {
    const OIIO::ROI size = OIIO::ImageBufAlgo::text_size(s.label, 14, kFont);
    legend_width = std::max(legend_width, size.defined() ? size.width() : 8 * static_cast<int>(s.label.size()));
  }
  const int legend_height = 22 * static_cast<int>(series.size()) + 8;
  const int box_w = 44 + legend_width;
  int lx = kLeft + 8, ly = kTop + 8, fewest = -1;
  for (int corner = 0; corner < 4; ++corner) {
    const int x0 = corner % 2 == 0 ? kLeft + 8 : std::max(kLeft + 8, w - kRight - 8 - box_w);
    const int y0 = corner < 2 ? kTop + 8 : h - kBottom - 8 - legend_height;
    int covered = 0;
    for (const PlotSeries& s : series)
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!ax.drawable(s.x[i]) || !ay.drawable(s.y[i])) continue;
        const double px = ax.pixel(s.x[i]), py = ay.pixel(s.y[i]);
        covered += px >= x0 - 10 && px <= x0 + box_w + 10 && py >= y0 - 10 && py <= y0 + legend_height + 10;
      }
    if (fewest < 0 || covered < fewest) fewest = covered, lx = x0, ly = y0;
  }
  OIIO::ImageBufAlgo::render_box(image, lx, ly, lx + box_w, ly + legend_height, kWhite, true);
  OIIO::ImageBufAlgo::render_box(image, lx, ly, lx + box_w, ly + legend_height, kGrid);
  int legend_y = ly + 18;
  for (const PlotSeries& s : series) {
    const OIIO::cspan<float> c(s.color.data(), 3);
    OIIO::ImageBufAlgo::render_line(image, lx + 8, legend_y - 4, lx + 32, legend_y - 4, c);
    OIIO::ImageBufAlgo::render_box(image, lx + 17, legend_y - 7, lx + 23, legend_y - 1, c, true);
    text(image, lx + 38, legend_y + 1, s.label, 14, AX::Left, AY::Baseline);
    legend_y += 22;
  }
}

void write_png(const std::string& path, const OIIO::ImageBuf& image) {
  write_file_atomically(path, [&](const std::string& temporary) {
    OIIO::ImageBuf out;
    OIIO::ImageBufAlgo::copy(out, image, OIIO::TypeDesc::UINT8);
    if (!out.write(temporary, OIIO::TypeDesc::UINT8, "png"))
      throw InputError(path + ": cannot write PNG: " + out.geterror());
  });
}

}  // namespace

void write_line_plot_png(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options) {
  const int w = options.width, h = options.height;
  Axis ax{options.log_x}, ay{options.log_y};
  fit_axes(path, series, options, ax, ay);

  OIIO::ImageBuf image(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::fill(image, kWhite);
  draw_grid_and_ticks(image, ax, ay, w, h);
  // Series: error bars, then lines (solid or dashed), then markers.
  for (const PlotSeries& s : series) draw_series(image, s, ax, ay);

  // Legend, labels, title.
  draw_legend(image, series, ax, ay, w, h);
  text(image, (kLeft + w - kRight) / 2, h - 18, options.x_label, 16, AX::Center, AY::Baseline);
  text(image, 8, kTop - 12, options.y_label, 16, AX::Left, AY::Baseline);
  text(image, (kLeft + w - kRight) / 2, 24, options.title, 18, AX::Center, AY::Baseline);
  write_png(path, image);
}

}  // namespace physarum
