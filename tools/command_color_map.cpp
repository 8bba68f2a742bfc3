// `physarum color_map IMAGE --out MAP.json [--strip STRIP.png] [--stops N]`: extracts a colour map
// from an exemplar picture (image-assisted colourisation, Sec. 3.4 of the paper; the method is in
// common/color/isomap_color_map.hpp) and writes it as a colour-map file that a scene's "colormap" key or
// `physarum render --color_map` can use, plus the map drawn as a strip to look at (low end left).
//
// The work is api/tools/color_map_from_image.hpp's; this file is the command's flags.
#include "api/tools/color_map_from_image.hpp"
#include "tools/commands.hpp"

#include <iostream>
#include <memory>
#include <string>

namespace physarum::cli {

Command add_color_map_command(CLI::App& parent) {
  auto options = std::make_shared<ColorMapFromImage>();
  CLI::App* app = parent.add_subcommand(
      "colormap",
      "Extract a colour map from an exemplar image\n"
      "Extract a colour map from an exemplar image (ISOMAP over its pixel colours + smoothing splines; the "
      "background, the dominant colour of the image's border, becomes the low end). Writes MAP.json (for a "
      "scene's \"colormap\" key or `physarum render --colormap`) and the map drawn as a strip. "
      "Example: physarum colormap lichen.jpg --out lichen.json");
  app->footer("Exit codes: 0 success, 1 bad input (an unreadable image; nothing is written), 2 usage error.");
  app->add_option("image", options->image, "Exemplar image (PNG, JPEG, ...)")->required();
  app->add_option("--out", options->out, "Colour-map file to write (JSON)")->required();
  app->add_option("--strip", options->strip, "Strip picture of the map (PNG; default: --out with .png)");
  app->add_option("--stops", options->stops, "Stops of the map, sampled regularly from the fitted curve")->capture_default_str();
  app->add_option("--strip-width", options->strip_width, "Strip width in pixels")->capture_default_str();
  app->add_option("--strip-height", options->strip_height, "Strip height in pixels")->capture_default_str();
  return Command{app, [options] {
                   std::cout << write_color_map_from_image(*options) << "\n";
                   return 0;
                 }};
}

}  // namespace physarum::cli
