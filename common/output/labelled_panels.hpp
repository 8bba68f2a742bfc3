#pragma once
// Pictures side by side: equal-sized panels in a grid, each under a one-line caption (DejaVu Sans
// when the font is installed; without it the panels are still drawn, uncaptioned). `physarum compare
// --out` shows the two arms' fields this way.
#include "common/output/preview_image.hpp"

#include <string>
#include <vector>

namespace physarum {

struct LabelledPanel {
  RgbImage image;
  std::string caption;
};

// The panels row by row, `columns` to a row, on white. InputError unless there is at least one
// panel, columns >= 1 and every panel has the first one's size.
RgbImage arrange_panels(const std::vector<LabelledPanel>& panels, int columns);

}  // namespace physarum
