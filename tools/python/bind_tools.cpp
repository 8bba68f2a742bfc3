// The whole tools of the command line, in-process on the library (api/): analyze a run folder,
// compare two arms, extract a colour map, grow a sketch. Each returns what the command writes
// (analysis.json, verdict.json, the summary line) and raises with the engine's own message; the
// engine's lines go to `log` (the package's logger). physarum/tools.py wraps them.
#include "api/comparison.hpp"
#include "api/sketch/sketch_run.hpp"
#include "api/tools/color_map_from_image.hpp"
#include "api/tools/run_analysis.hpp"
#include "common/base/errors.hpp"
#include "tools/python/bindings.hpp"

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>

namespace physarum::python {

SurfaceNote python_log(nb::object log) {
  if (log.is_none()) return {};
  auto callable = std::make_shared<nb::object>(std::move(log));
  return [callable](const std::string& line) {
    nb::gil_scoped_acquire locked;
    try {
      (*callable)(line);
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("physarum's log");  // a failing log handler must not stop the engine
    }
  };
}

PatternAnalysisRequest analysis_request(const std::string& field, std::optional<double> threshold, bool below,
                                        double min_area) {
  PatternAnalysisRequest r;
  r.field = field;
  r.threshold = threshold;
  r.below = below;
  r.min_area = min_area;
  return r;
}

void bind_tools(nb::module_& m) {
  m.def(
      "_analyze_folder",
      [](const std::string& run_dir, const std::string& field, std::optional<double> threshold, bool below,
         double min_area) {
        nb::gil_scoped_release unlocked;
        return analyze_run_folder(run_dir, analysis_request(field, threshold, below, min_area)).json.dump();
      },
      nb::arg("run_dir"), nb::arg("field"), nb::arg("threshold").none(), nb::arg("below"), nb::arg("min_area"));
  m.def(
      "_compare",
      [](const std::string& scene, const std::vector<std::string>& arms, std::optional<int> seeds, int jobs,
         const std::string& device, const std::string& fault, const std::string& out, nb::object log) {
        ComparisonRequest r;
        r.scene = scene;
        r.arms = arms;
        r.max_seeds = seeds;
        r.jobs = jobs;
        r.device = device;
        r.fault = fault;
        r.out = out;
        r.log = python_log(std::move(log));
        ComparisonResult result;
        {
          nb::gil_scoped_release unlocked;
          result = compare(r);
        }
        if (result.drift) throw InputError(*result.drift);
        return nb::make_tuple(result.exit_code, result.verdict.dump());
      },
      nb::arg("scene"), nb::arg("arms"), nb::arg("seeds").none(), nb::arg("jobs"), nb::arg("device"), nb::arg("fault"),
      nb::arg("out"), nb::arg("log").none());
  m.def(
      "_colormap",
      [](const std::string& image, const std::string& out, int stops) {
        ColorMapFromImage r;
        r.image = image;
        r.out = out;
        r.stops = stops;
        nb::gil_scoped_release unlocked;
        return write_color_map_from_image(r);
      },
      nb::arg("image"), nb::arg("out"), nb::arg("stops"));
  // sketch(): the request as a dict of physarum sketch's options (keys as SketchRequest's fields).
  m.def(
      "_sketch",
      [](const std::string& sketch, const std::string& out, const nb::dict& options, nb::object log) {
        SketchRequest r;
        r.sketch = sketch;
        r.out = out;
        for (auto [key, value] : options) {
          const std::string k = nb::cast<std::string>(key);
          if (k == "mesh") r.mesh = nb::cast<std::string>(value);
          else if (k == "model") r.model = nb::cast<std::string>(value);
          else if (k == "regions") r.regions = nb::cast<int>(value);
          else if (k == "area") r.area = nb::cast<double>(value);
          else if (k == "max_circumradius") r.max_circumradius = nb::cast<double>(value);
          else if (k == "refine") r.refine = nb::cast<int>(value);
          else if (k == "seed") r.seed = nb::cast<std::uint32_t>(value);
          else if (k == "backend") r.backend = nb::cast<std::string>(value);
          else if (k == "device") r.device = nb::cast<std::string>(value);
          else if (k == "layer2") r.layer2 = nb::cast<std::string>(value);
          else if (k == "rosettes") r.rosettes = nb::cast<bool>(value);
          else if (k == "colors") r.colors = nb::cast<std::vector<std::string>>(value);
          else if (k == "uv") r.uv = nb::cast<bool>(value);
          else throw nb::value_error(("sketch: unknown option '" + k + "'").c_str());
        }
        r.log = python_log(std::move(log));
        nb::gil_scoped_release unlocked;
        return run_sketch(r);
      },
      nb::arg("sketch"), nb::arg("out"), nb::arg("options"), nb::arg("log").none());
}

}  // namespace physarum::python
