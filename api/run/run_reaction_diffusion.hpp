#pragma once
// `physarum run` for a reaction-diffusion scene (common/scene/scene_reaction_diffusion.hpp; its
// preparation is prepare_reaction_diffusion_run in api/run/prepared_run.hpp): the same
// command, flags, run loop (api/run/run_loop.hpp) and output files as for the agent model, with the
// morphogens as the fields:
//   DIR/morphogens.ply    the input mesh with every morphogen as a float vertex property of its name
//                         (the preview morphogen first: the vertex colours are its),
//   DIR/fields_full.ply   the same at full resolution (every intrinsic vertex, exact values),
//   DIR/preview.png       the preview morphogen ("preview_morphogen", default the second), coloured
//                         over 0 .. its largest final value (levels in multiples of half of it),
//   DIR/texture.png, DIR/result.glb   the preview morphogen baked / exported as for the agent model,
//   DIR/stats.csv         time,<m>_mean,<m>_variance,... per morphogen (area-weighted over the surface),
//   DIR/run.json          model, morphogens, steps, seconds, sub-steps, the system as run, the surface;
// with --maps-out FILE the scene's maps on the input mesh (written before simulating, as for agents).
// The maps come through the map cache (common/setup/cached_map_evaluation.hpp), as for the agent model.
// With --checkpoint-every T, DIR/checkpoint.bin holds every morphogen (the backend's save_state)
// every T simulated seconds; `physarum run --resume DIR` continues bit for bit and writes what the
// uninterrupted run would have (tools/run/command_run.cpp says the rules; they are the agent model's).
// As for the agent model, everything that can reject the input happens before DIR is touched, and
// every file is written under a temporary name and renamed.
#include "common/base/element_data.hpp"
#include "common/scene/scene.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "api/run/resume_point.hpp"
#include "api/run/run_options.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// The colours' unit of a layer: half its largest value (levels in multiples of it), so the picture
// uses the whole colour map whatever the model's units; 1 for a layer with nothing above zero.
double morphogen_color_unit(const std::vector<double>& values);

// InputError naming `source` and the morphogen when a dynamic layer is no longer finite (the run
// diverged), with what to change.
void check_morphogens_finite(const SimulationBackend& simulation, const std::vector<std::string>& morphogens,
                             const std::string& source);

// stats.csv's header and one row: the area-weighted mean and variance of every morphogen.
std::string morphogen_stats_header(const std::vector<std::string>& morphogens);
std::string morphogen_stats_row(double time, const std::vector<IntrinsicVertexData<double>>& layers,
                                const IntrinsicVertexData<double>& mass);

}  // namespace physarum
