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
// The work is api/sketch/sketch_run.hpp's; this file is the command's flags.
#include "api/sketch/sketch_run.hpp"
#include "tools/commands.hpp"

#include <iostream>
#include <memory>

namespace physarum::cli {

Command add_sketch_command(CLI::App& parent) {
  auto options = std::make_shared<SketchRequest>();
  CLI::App* app = parent.add_subcommand(
      "sketch",
      "Grow a reaction-diffusion texture whose spots or stripes follow drawn ones, and check it\n"
      "Sketch a pattern (paper 004): SKETCH is a PNG (dark marks on a light background; filled or outlined "
      "blobs are spots, long thin or red marks strokes) or a JSON sketch of ellipses and strokes, or of ellipses "
      "on the mesh's surface (\"surface_point\": each mark a region, blended by geodesic distance). Its window "
      "maps onto the mesh's x/y extent, or with --uv onto its UV layout; the window is divided into --regions x --regions regions, each region's "
      "spot area goes through the model's inverse map (learned from tools/sketch/make_training_data.sh's runs) "
      "to a reaction rate, blended over the surface. Writes DIR/scene.json (the generated scene, runnable with "
      "physarum run), DIR/sketch_maps.ply (its rate map), DIR/sketch.png (the marks as measured), the run's files, DIR/sketch.json (every mark's "
      "attributes, the regions, the map) and DIR/report.json (per region the sketched and the generated area, "
      "aspect, orientation and spacing, with a verdict). Elongated spots: both morphogens diffuse aspect^2 as fast "
      "across the sketched orientations (blended between regions) as along them. Strokes "
      "(meinhardt-stripes, the default for a sketch of strokes alone): each region's stroke orientation and width "
      "class (k x 2.5 % of the window's width) give the stripes' rate and initiator cells, random segments along the "
      "blended orientations from which the stripes grow; report.json judges their orientation and width. "
      "--layer2 SKETCH2 grows a second sketch's spots between the first's, frozen (--rosettes: around them, reset), "
      "the first layer in DIR/layer1; --colors SET1 [SET2] draws each layer in its own colour set. Example: physarum sketch "
      "tools/sketch/examples/four_sizes.json --out sketch");
  app->add_option("sketch", options->sketch, "The sketch: a PNG or a JSON sketch")->required();
  app->add_option("--mesh", options->mesh, "The surface (a mesh file or shape:NAME); default shape:square");
  app->add_flag("--uv", options->uv,
                "The sketch is painted on the mesh's UV layout (the window onto UV [0, 1]^2, a PNG's top row at v = 1), "
                "measured on the surface through the layout's stretch; the mesh must have texture coordinates");
  app->add_option("--model", options->model,
                  "turing-spots, meinhardt-spots or meinhardt-stripes (default: turing-spots for a sketch with spots, "
                  "meinhardt-stripes for one of strokes alone)");
  app->add_option("--regions", options->regions,
                  "Regions per side of the window (default 2: the paper's four); marks on the surface are a region each");
  app->add_option("--area", options->area, "The surface's area in m^2 (scale_to_area; default 1)");
  app->add_option("--max-circumradius", options->max_circumradius,
                  "The mesh resolution in m (default 0.007, the training's: about the models' 1 cm cell)");
  app->add_option("--refine", options->refine, "Correct missed regions' rates and run again, up to K times (default 0)");
  app->add_option("--seed", options->seed, "The run's seed (default 1)");
  app->add_option("--backend", options->backend, "auto, reference or opencl")->check(CLI::IsMember({"auto", "reference", "opencl"}));
  app->add_option("--device", options->device, "The OpenCL device (default: $PHYSARUM_DEVICE, else the first)");
  app->add_option("--out", options->out, "Output folder (default sketch)");
  CLI::Option* layer2 = app->add_option(
      "--layer2", options->layer2,
      "A second sketch of (smaller) spots grown between the first's, frozen: the first layer runs in DIR/layer1, "
      "the second in DIR; report.json's layer2 says whether any new spot touches a frozen one");
  app->add_flag("--rosettes", options->rosettes,
                "With --layer2: reset the frozen spots to the uniform state, so that the new spots ring them (Turk's leopard)")
      ->needs(layer2);
  app->add_option("--colors", options->colors,
                  "A colour set per layer, each spread from the layer's valley to its peak: a colour-map name, a MAP.json "
                  "or \"#rrggbb,#rrggbb,...\"; redraws preview.png, view_front.png, texture.png and result.glb, with "
                  "--layer2 the first layer's spots in SET1 and the rest in SET2")
      ->expected(1, 2);
  app->footer("Exit codes: 0 success (report.json says how well each region matched), 1 bad input (a bad sketch, "
              "spots too small for the mesh or outside what the training covers: nothing is run), 2 usage error.");
  return {app, [options] {
            SketchRequest request = *options;
            request.log = [](const std::string& line) { std::cerr << line << "\n"; };
            std::cout << run_sketch(request) << "\n";
            return 0;
          }};
}

}  // namespace physarum::cli
