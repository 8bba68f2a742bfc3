#pragma once
// `physarum run` for a reaction-diffusion scene (common/scene_reaction_diffusion.hpp): the same
// command, flags and output files as for the agent model, with the morphogens as the fields:
//   DIR/pheromone.ply     the input mesh with every morphogen as a float vertex property of its name
//                         (the preview morphogen first: the vertex colours are its),
//   DIR/fields_full.ply   the same at full resolution (every intrinsic vertex, exact values),
//   DIR/preview.png       the preview morphogen ("preview_morphogen", default the second), coloured
//                         over 0 .. its largest final value (levels in multiples of half of it),
//   DIR/texture.png, DIR/result.glb   the preview morphogen baked / exported as for the agent model,
//   DIR/stats.csv         time,<m>_mean,<m>_variance,... per morphogen (area-weighted over the surface),
//   DIR/run.json          model, morphogens, steps, seconds, sub-steps, the system as run, the surface.
// As for the agent model, everything that can reject the input happens before DIR is touched, and
// every file is written under a temporary name and renamed.
#include "common/scene.hpp"
#include "tools/surface_exports.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace physarum::cli {

struct ReactionDiffusionRunOptions {
  std::string scene_path;
  std::string backend = "auto";  // auto | reference | opencl, as for the agent model
  std::string device;            // --device SPEC
  long long steps = 0;                // the run length, already resolved
  std::string out = "out";
  int frames = 0;
  TextureSettings texture;
};

int run_reaction_diffusion(const Scene& scene, const ReactionDiffusionRunOptions& options);

// stats.csv's header and one row: the area-weighted mean and variance of every morphogen.
std::string morphogen_stats_header(const std::vector<std::string>& morphogens);
std::string morphogen_stats_row(double time, const std::vector<IntrinsicVertexData<double>>& layers,
                                const IntrinsicVertexData<double>& mass);

}  // namespace physarum::cli
