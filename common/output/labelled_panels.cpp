#include "common/output/labelled_panels.hpp"

#include "common/base/errors.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cstring>

namespace physarum {
namespace {

constexpr int kCaptionHeight = 30;
constexpr int kCaptionSize = 16;

}  // namespace

RgbImage arrange_panels(const std::vector<LabelledPanel>& panels, int columns) {
  if (panels.empty() || columns < 1) throw InputError("arrange_panels: no panels, or fewer than one column");
  const int w = panels.front().image.width, h = panels.front().image.height;
  for (const LabelledPanel& p : panels)
    if (p.image.width != w || p.image.height != h || p.image.pixels.size() != static_cast<size_t>(w) * h * 3)
      throw InputError("arrange_panels: the panels differ in size");
  const int cols = std::min(columns, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + cols - 1) / cols;
  const int cell_h = h + kCaptionHeight;
  OIIO::ImageBuf canvas(OIIO::ImageSpec(cols * w, rows * cell_h, 3, OIIO::TypeDesc::UINT8));
  const float white[3] = {1.0f, 1.0f, 1.0f};
  OIIO::ImageBufAlgo::fill(canvas, white);
  for (size_t i = 0; i < panels.size(); ++i) {
    const int x0 = static_cast<int>(i) % cols * w, y0 = static_cast<int>(i) / cols * cell_h;
    const OIIO::ImageBuf panel(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8),
                               const_cast<std::uint8_t*>(panels[i].image.pixels.data()));
    OIIO::ImageBufAlgo::paste(canvas, x0, y0 + kCaptionHeight, 0, 0, panel);
    const float ink[3] = {0.1f, 0.1f, 0.1f};
    OIIO::ImageBufAlgo::render_text(canvas, x0 + w / 2, y0 + kCaptionHeight - 9, panels[i].caption, kCaptionSize,
                                    "DejaVuSans", ink, OIIO::ImageBufAlgo::TextAlignX::Center,
                                    OIIO::ImageBufAlgo::TextAlignY::Baseline);
  }
  RgbImage out;
  out.width = cols * w;
  out.height = rows * cell_h;
  out.pixels.resize(static_cast<size_t>(out.width) * out.height * 3);
  canvas.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, out.pixels.data());
  return out;
}

}  // namespace physarum
