#include "api/tools/color_map_from_image.hpp"

#include "common/base/errors.hpp"
#include "common/color/color_map_json.hpp"
#include "common/color/isomap_color_map.hpp"
#include "common/output/color_map_strip.hpp"

#include <filesystem>

namespace physarum {

namespace fs = std::filesystem;

std::string write_color_map_from_image(const ColorMapFromImage& o) {
  if (o.stops < 2 || o.stops > 65536) throw UsageError("--stops " + std::to_string(o.stops) + " must be in 2..65536");
  const fs::path out(o.out);
  if (out.extension() == ".png") throw UsageError("--out " + o.out + ": the colour map is JSON (use --strip for the PNG)");
  const std::string strip = o.strip.empty() ? fs::path(out).replace_extension(".png").string() : o.strip;
  if (fs::path(strip) == out) throw UsageError("--strip and --out name the same file " + o.out);
  // `physarum colormap lichen.png --out lichen.json` would draw its strip over the exemplar itself.
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
  return "physarum colormap: " + o.image + ": " + std::to_string(extracted.graph_nodes) + " distinct colours, background " +
         hex_color(to_rgb8(extracted.background)) + " at t = 0; wrote " + out.string() + " (" + std::to_string(o.stops) +
         " stops) and " + strip;
}

}  // namespace physarum
