#pragma once
// `physarum sketch SKETCH`: from drawn spots or strokes to a reaction-diffusion texture like them
// (004, Phan & Grimm), which checks its own result. The sketch (a PNG or the JSON form,
// common/sketch/sketch.hpp) is measured and divided into regions (common/sketch/sketch_regions.hpp);
// each region's spot area or stripe width goes through the model's inverse map to a reaction rate
// (api/sketch/sketch_plan.hpp), the generated scene is written and run as `physarum run` runs it,
// and the grown spots (api/sketch/sketch_report.hpp) or stripes (api/sketch/stripe_report.hpp)
// are measured per region against the sketch; --refine K corrects each missed region's rate by its
// miss and runs again, up to K times. --layer2 grows a second sketch's spots on the first's frozen
// ones (api/sketch/sketch_layers.hpp). The window lies on a patch or a UV layout, or the marks on
// the surface itself (common/sketch/sketch_domain.hpp, common/sketch/surface_marks.hpp).
//
// `physarum sketch` is this function with its flags (tools/sketch/command_sketch.cpp); the Python
// module's sketch() calls it in-process.
#include "api/sketch/sketch_plan.hpp"
#include "common/surface/prepared_surface.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace physarum {

struct SketchRequest {
  std::string sketch;
  std::string mesh = "shape:square";
  std::string model;  // empty: default_model
  int regions = 2;
  double area = 1.0;
  double max_circumradius = kTrainingCircumradius;
  int refine = 0;
  std::uint32_t seed = 1;
  std::string backend = "auto";
  std::string device;
  std::string out = "sketch";
  std::string layer2;     // a second sketch: smaller spots between the first's, frozen (api/sketch/sketch_layers.hpp)
  bool rosettes = false;  // the frozen spots reset to the uniform state: the new spots ring them
  std::vector<std::string> colors;  // a colour set per layer (api/sketch/sketch_colours.hpp)
  bool uv = false;  // the window is the mesh's UV layout (common/sketch/sketch_domain.hpp)
  SurfaceNote log;  // the runs' notes (physarum run's); none: quiet
};

// Everything that can refuse the sketch (UsageError, InputError) before any output exists; then the
// runs and DIR's files (sketch.png, sketch.json, scene.json, report.json, sketch_maps.ply and the
// run's files). Returns the closing line: the model, the regions, the runs, how many passed.
std::string run_sketch(const SketchRequest& request);

}  // namespace physarum
