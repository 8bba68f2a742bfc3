#pragma once
// A colour map extracted from an exemplar picture (image-assisted colourisation, Sec. 3.4 of paper
// 000; the method is common/color/isomap_color_map.hpp), written as a colour-map file that a scene's
// "colormap" key or `physarum render --colormap` reads, with the map drawn as a strip beside it (low
// end left). `physarum colormap` and the Python module's colormap() are this function.
#include <string>

namespace physarum {

struct ColorMapFromImage {
  std::string image;      // the exemplar (PNG, JPEG, ...)
  std::string out;        // the colour-map file (JSON)
  std::string strip;      // its picture; "": beside `out`, with .png
  int stops = 256;        // sampled regularly from the fitted curve, 2 .. 65536
  int strip_width = 512, strip_height = 64;
};

// Reads the image and builds the map before anything is written (UsageError on bad arguments, InputError
// on an unreadable image or one of fewer than two colours: nothing is written then), writes both files
// under temporary names and renames them; returns the one-line summary
// ("physarum colormap: IMAGE: N distinct colours, background #rrggbb at t = 0; wrote ...").
std::string write_color_map_from_image(const ColorMapFromImage& request);

}  // namespace physarum
