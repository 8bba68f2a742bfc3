#include "tools/sweep/contact_sheet.hpp"

#include "common/base/errors.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace physarum::cli {
namespace {

constexpr const char* kFont = "DejaVuSans";
constexpr int kFontSize = 15;

// Text in dark grey; false when the font is missing (the caller notes it once).
bool text(OIIO::ImageBuf& image, int x, int y, const std::string& s, OIIO::ImageBufAlgo::TextAlignX ax) {
  if (s.empty()) return true;
  const float ink[3] = {0.1f, 0.1f, 0.1f};
  return OIIO::ImageBufAlgo::render_text(image, x, y, s, kFontSize, kFont, ink, ax, OIIO::ImageBufAlgo::TextAlignY::Center);
}

// The preview shrunk to fit a size x size square, centred in it.
void paste_thumbnail(OIIO::ImageBuf& sheet, const std::string& path, int x, int y, int size) {
  OIIO::ImageBuf source(path);
  if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT))
    throw InputError(path + ": cannot read the preview: " + source.geterror());
  const OIIO::ImageSpec& spec = source.spec();
  const double scale = std::min(static_cast<double>(size) / spec.width, static_cast<double>(size) / spec.height);
  const int w = std::max(1, static_cast<int>(spec.width * scale)), h = std::max(1, static_cast<int>(spec.height * scale));
  OIIO::ImageBuf small = OIIO::ImageBufAlgo::resize(source, "", 0.0f, OIIO::ROI(0, w, 0, h, 0, 1, 0, spec.nchannels));
  if (small.nchannels() != 3) small = OIIO::ImageBufAlgo::channels(small, 3, {0, 1, 2});
  OIIO::ImageBufAlgo::paste(sheet, x + (size - w) / 2, y + (size - h) / 2, 0, 0, small);
}

}  // namespace

int row_label_width_for(const std::vector<std::string>& labels) {
  std::size_t longest = 0;
  for (const std::string& l : labels) longest = std::max(longest, l.size());
  // DejaVu Sans at 15 px averages under 9 px per character; a margin on both sides.
  return longest == 0 ? 0 : static_cast<int>(std::min<std::size_t>(longest, 48)) * 9 + 16;
}

RgbImage draw_contact_sheet(const ContactSheet& sheet) {
  const ContactSheetLayout& L = sheet.layout;
  if (L.rows < 1 || L.columns < 1 || L.seeds < 1 || L.thumbnail < 8)
    throw UsageError("contact sheet: needs at least one row, column and seed and thumbnails of 8 px or more");
  OIIO::ImageBuf image(OIIO::ImageSpec(L.width(), L.height(), 3, OIIO::TypeDesc::FLOAT));
  const float white[3] = {1.0f, 1.0f, 1.0f}, grey[3] = {0.85f, 0.85f, 0.85f};
  OIIO::ImageBufAlgo::fill(image, white);

  bool labelled = text(image, L.gap, L.header_height / 4, sheet.title, OIIO::ImageBufAlgo::TextAlignX::Left);
  for (int c = 0; c < L.columns; ++c) {
    const int centre = L.cell_x(c, 0) + L.seeds * L.thumbnail / 2;
    labelled &= text(image, centre, 3 * L.header_height / 4, sheet.column_labels.at(static_cast<std::size_t>(c)),
                     OIIO::ImageBufAlgo::TextAlignX::Center);
  }
  for (int r = 0; r < L.rows; ++r) {
    const std::string& label = sheet.row_labels.at(static_cast<std::size_t>(r));
    labelled &= text(image, L.gap, L.cell_y(r) + L.thumbnail / 2, label, OIIO::ImageBufAlgo::TextAlignX::Left);
    for (int c = 0; c < L.columns; ++c) {
      for (int s = 0; s < L.seeds; ++s) {
        const std::string& path = sheet.previews.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(c)).at(static_cast<std::size_t>(s));
        const int x = L.cell_x(c, s), y = L.cell_y(r);
        if (!path.empty() && std::filesystem::exists(path)) {
          paste_thumbnail(image, path, x, y, L.thumbnail);
        } else {
          OIIO::ImageBufAlgo::fill(image, grey, OIIO::ROI(x + 1, x + L.thumbnail - 1, y + 1, y + L.thumbnail - 1, 0, 1, 0, 3));
          labelled &= text(image, x + L.thumbnail / 2, y + L.thumbnail / 2, "missing", OIIO::ImageBufAlgo::TextAlignX::Center);
        }
      }
    }
  }
  if (!labelled)
    std::cerr << "physarum sweep: note: the font DejaVu Sans was not found (install fonts-dejavu-core): the contact "
                 "sheet is drawn without its labels\n";
  RgbImage out;
  out.width = L.width();
  out.height = L.height();
  out.pixels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 3);
  image.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, out.pixels.data());
  return out;
}

}  // namespace physarum::cli
