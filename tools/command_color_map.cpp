// `physarum color_map IMAGE --out MAP.json [--strip STRIP.png] [--stops N]`: extracts a colour map
// from an exemplar picture (image-assisted colourisation, Sec. 3.4 of the paper; the method is in
// common/color/isomap_color_map.hpp) and writes it as a colour-map file that a scene's "colormap" key or
// `physarum render --color_map` can use, plus the map drawn as a strip to look at (low end left).
//
// The image is read and the map built before anything is written, and both files are written under
// temporary names and renamed, so an unreadable image leaves nothing behind.
#include "common/color/color_map_json.hpp"
#include "common/output/color_map_strip.hpp"
#include "common/base/errors.hpp"
#include "common/color/isomap_color_map.hpp"
#include "tools/commands.hpp"

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

struct ColorMapOptions {
  std::string image;
  std::string out;
  std::string strip;  // "" = beside MAP.json, with .png
  int stops = 256;
  int strip_width = 512;
  int strip_height = 64;
};

int run_color_map(const ColorMapOptions& o) {
  if (o.stops < 2 || o.stops > 65536) throw UsageError("--stops " + std::to_string(o.stops) + " must be in 2..65536");
  const fs::path out(o.out);
  if (out.extension() == ".png") throw UsageError("--out " + o.out + ": the colour map is JSON (use --strip for the PNG)");
  const std::string strip = o.strip.empty() ? fs::path(out).replace_extension(".png").string() : o.strip;
  if (fs::path(strip) == out) throw UsageError("--strip and --out name the same file " + o.out);
  // `physarum color_map lichen.png --out lichen.json` would draw its strip over the exemplar itself.
  std::error_code ec;
  if (fs::path(strip).lexically_normal() == fs::path(o.image).lexically_normal() || fs::equivalent(strip, o.image, ec))
    throw UsageError("the strip " + strip + " would overwrite the image " + o.image + " (give --strip)");

  IsomapOptions options;
  options.stops = o.stops;
  const IsomapColorMap extracted = isomap_color_map_from_image(o.image, options);
  ColorMapSettings settings;
  settings.map = extracted.map;
  // Check the strip's size before writing anything.
  const RgbImage picture = color_map_strip(settings.map, o.strip_width, o.strip_height);

  for (const fs::path& file : {out, fs::path(strip)})
    if (file.has_parent_path() && !fs::is_directory(file.parent_path()))
      throw InputError(file.string() + ": cannot write: folder " + file.parent_path().string() + " does not exist");
  write_color_map_file(out.string(), settings);
  write_rgb_png(strip, picture);
  const Rgb8 background = to_rgb8(extracted.background);
  std::cout << "physarum colormap: " << o.image << ": " << extracted.graph_nodes << " distinct colours, background "
            << hex_color(background) << " at t = 0; wrote " << out.string() << " (" << o.stops << " stops) and " << strip
            << "\n";
  return 0;
}

}  // namespace

Command add_color_map_command(CLI::App& parent) {
  auto options = std::make_shared<ColorMapOptions>();
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
  return Command{app, [options] { return run_color_map(*options); }};
}

}  // namespace physarum::cli
