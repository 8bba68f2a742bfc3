#pragma once
// `physarum sketch --colors SET1 [SET2]` (paper 004, Sec. 2.3, Figs. 7-8): each layer of the grown
// pattern in its own colour set, spread from the layer's valley to its peak
// (common/color/layer_colours.hpp). A set is a built-in colour-map name, a MAP.json file or a list of
// colours "#rrggbb,#rrggbb,..."; its levels, if any, are not used. After a run, the output folder's
// preview.png, view_front.png (the patch seen face on, from +z), texture.png (where the mesh has UVs)
// and result.glb are drawn again in the sets; with two layers they composite the first layer's
// frozen spots in SET1 and the rest of the final field in SET2 (SET1 for both when SET2 is not given).
// The PLY files keep the run's own colour map.
#include "common/color/color_map_json.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// The sets of --colors, parsed: InputError naming the option and the set for a bad one; UsageError
// for more than two.
std::vector<ColorMapSettings> read_colour_sets(const std::vector<std::string>& specs);

// The first layer of a two-layer result: its folder (its fields_full.ply and morphogens.ply) and the
// threshold above which its spots were frozen.
struct FirstLayerColours {
  std::filesystem::path folder;
  double threshold = 0.0;
};

// Redraws `folder`'s pictures and exports (the run's files there: run.json, fields_full.ply,
// morphogens.ply) with `field` in `set`, or, given `first`, composited with the first layer's spots
// in `first_set`. Returns the names written.
std::vector<std::string> write_layer_colours(const std::filesystem::path& folder, const std::string& field,
                                             const ColorMapSettings& set,
                                             const std::optional<FirstLayerColours>& first = std::nullopt,
                                             const ColorMapSettings& first_set = {});

}  // namespace physarum
