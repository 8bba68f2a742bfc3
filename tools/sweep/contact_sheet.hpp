#pragma once
// The contact sheet of a parameter study (`physarum sweep --collect`): every run's preview.png,
// shrunk to a thumbnail, in a grid whose rows and columns are values of the varied keys, labelled
// with them (Fig. 8 of the paper is one). Within a cell the seeds of one variant stand side by side.
//
// Layout, in pixels (so a reader can find a cell, and the tests check the size):
//   width  = row_label_width + columns * (seeds * thumbnail + gap) + gap
//   height = header_height   + rows    * (thumbnail + gap) + gap
// row_label_width is 0 when the rows carry no labels (one row). Thumbnails keep their preview's
// aspect ratio, centred in a thumbnail x thumbnail square. Labels are drawn in DejaVu Sans
// (fonts-dejavu-core); without the font the sheet is drawn unlabelled, with a note on stderr.
#include "common/output/preview_image.hpp"

#include <string>
#include <vector>

namespace physarum::cli {

struct ContactSheetLayout {
  int rows = 1, columns = 1, seeds = 1;
  int thumbnail = 160;
  int gap = 8;
  int header_height = 48;
  int row_label_width = 0;

  int width() const { return row_label_width + columns * (seeds * thumbnail + gap) + gap; }
  int height() const { return header_height + rows * (thumbnail + gap) + gap; }
  // Top-left corner of seed s's thumbnail in cell (row, column).
  int cell_x(int column, int seed) const { return row_label_width + gap + column * (seeds * thumbnail + gap) + seed * thumbnail; }
  int cell_y(int row) const { return header_height + gap + row * (thumbnail + gap); }
};

struct ContactSheet {
  ContactSheetLayout layout;
  std::string title;                        // above everything, e.g. "rows: turn_rate   columns: sensor_angle"
  std::vector<std::string> row_labels;      // one per row ("" when the rows carry no label)
  std::vector<std::string> column_labels;   // one per column
  // previews[row][column][seed]: a preview.png path, "" where the run is missing (drawn grey).
  std::vector<std::vector<std::vector<std::string>>> previews;
};

// The width a row label column needs for these labels (0 when all are empty).
int row_label_width_for(const std::vector<std::string>& labels);

// Draws the sheet. InputError naming a preview that exists but cannot be read.
RgbImage draw_contact_sheet(const ContactSheet& sheet);

}  // namespace physarum::cli
