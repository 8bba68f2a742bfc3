#pragma once
// `physarum run` for a growth scene (common/scene/scene_growth.hpp, paper 003): the same command,
// flags, run loop (tools/run/run_loop.hpp) and file names as for a reaction–diffusion scene, on the
// sheet as it has grown (api/growth_simulation.hpp):
//   DIR/morphogens.ply, DIR/fields_full.ply   the grown, deformed sheet (its own vertices: the two
//                         files hold the same mesh) with every morphogen, "area_growth" (rest area
//                         now / at the start, per vertex) and "stretch" (its square root: the linear
//                         growth) as float vertex properties; the colours are the preview morphogen's
//   DIR/preview.png, DIR/result.glb   the grown shape coloured by the preview morphogen, or by the
//                         area growth when the growth is prescribed and nothing reacts
//   DIR/stats.csv         time, growth_step, vertices, rest_area, then each morphogen's area-weighted
//                         mean and variance on the rest metric
//   DIR/run.json          growth_steps, area_growth, newton_iterations (per growth step), energy,
//                         vertices (per growth step), the growth records, the spec as run
//   with --frames K: DIR/frames/frame_NNNN.png and .ply (the sheet at that frame) and DIR/frames.gif.
// A growth step whose equilibrium solve fails stops the run: the outputs are written for the last
// converged sheet, the error says which step and what to change, and the exit status is 1.
#include "common/scene/scene.hpp"
#include "tools/run/resume_point.hpp"
#include "tools/run/run_options.hpp"

#include <optional>

namespace physarum::cli {

int run_growth(const Scene& scene, const RunOptions& options, long long steps, const std::optional<ResumePoint>& resume);

}  // namespace physarum::cli
