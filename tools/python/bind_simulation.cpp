// _Simulation: a scene's run exactly as `physarum run` makes it (api/run/prepared_run.hpp: the same
// session, run loop and writers), stepped from Python. The GIL is released while stepping, and
// Ctrl-C (SIGINT) stops a long step() between two steps, leaving a consistent state.
#include "api/growth_simulation.hpp"
#include "common/base/errors.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/scene/scene.hpp"
#include "tools/python/bindings.hpp"
#include "tools/python/numpy_arrays.hpp"
#include "api/run/prepared_run.hpp"

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace physarum::python {

namespace {

using Clock = std::chrono::steady_clock;

// How long the module steps without looking at Python: a Ctrl-C is seen within about this much
// (plus one step), and progress callbacks come no more often.
constexpr auto kCheckEvery = std::chrono::milliseconds(100);

class PythonSimulation {
 public:
  // `scene_file` when the scene is a file (loaded as `physarum run` loads it), else `scene_json`
  // (named `source` in messages; relative paths from the working directory).
  PythonSimulation(const std::string& scene_file, const std::string& scene_json, const std::string& backend,
                   const std::string& device, std::optional<std::uint32_t> seed, std::optional<long long> steps,
                   nb::object log) {
    RunOptions o;
    o.log = python_log(std::move(log));
    o.scene = scene_file;
    o.scene_text = scene_file.empty() ? scene_json : std::string();
    o.backend = backend;
    o.device = device;
    o.seed = seed;
    o.steps = steps;
    if (backend != "auto" && backend != "reference" && backend != "opencl")
      throw nb::value_error(("backend: '" + backend + "' is not auto, reference or opencl").c_str());
    if (!device.empty() && backend == "reference") throw nb::value_error("device: applies to the OpenCL backend only");
    if (steps && *steps < 1) throw nb::value_error("steps: must be >= 1");
    nb::gil_scoped_release unlocked;  // the surface and the maps can take seconds
    Scene scene = scene_file.empty() ? scene_from_json(nlohmann::json::parse(scene_json), "scene") : load_scene(scene_file);
    if (seed) scene.seed = *seed;
    run_ = prepare_run(scene, o, run_length_in_steps(o, scene), std::nullopt);
  }

  long long step(long long n, const nb::object& progress) {
    RunLoop& loop = run_->loop();
    if (n < 0) throw nb::value_error("n: must be >= 0");
    const long long left = loop.planned_steps() - loop.steps_taken();
    if (n > left)
      throw nb::value_error(("n: " + std::to_string(n) + " steps asked, " + std::to_string(left) + " left of the run's " +
                             std::to_string(loop.planned_steps()) + " (Simulation(steps=...) sets the length)")
                                .c_str());
    long long done = 0;
    bool running = true;
    while (running && done < n) {
      {
        nb::gil_scoped_release unlocked;
        const auto until = Clock::now() + kCheckEvery;
        while (done < n && (running = loop.step())) {
          ++done;
          if (Clock::now() >= until) break;
        }
      }
      if (PyErr_CheckSignals() != 0) throw nb::python_error();  // Ctrl-C: KeyboardInterrupt, between steps
      if (!progress.is_none()) progress(done, n);
    }
    return done;
  }

  nb::dict fields(const std::string& on) {
    if (on != "input" && on != "intrinsic" && on != "full")
      throw nb::value_error(("on: '" + on + "' is not input, intrinsic or full").c_str());
    Session& session = run_->session();
    nb::dict out;
    const std::vector<std::string>& names = session.layer_names();
    for (int layer = 0; layer < static_cast<int>(names.size()); ++layer) {
      std::vector<double> values;
      {
        nb::gil_scoped_release unlocked;
        values = on == "input" ? std::move(session.field_on_input(layer).values()) : std::move(session.field(layer).values());
      }
      out[names[static_cast<size_t>(layer)].c_str()] = to_numpy(std::move(values));
    }
    return out;
  }

  // Replaces the layer named `name` by `values`: per input vertex ("input", interpolated onto the
  // intrinsic vertices) or per intrinsic vertex ("intrinsic"; a growth run's: per vertex of its sheet
  // now). The sizes are checked here, so a wrong one names what was expected.
  void set_field(const std::string& name, std::vector<double> values, const std::string& on) {
    Session& session = run_->session();
    const std::vector<std::string>& names = session.layer_names();
    const auto found = std::find(names.begin(), names.end(), name);
    if (found == names.end()) {
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      throw nb::value_error(("set_field: no layer '" + name + "' (the layers: " + known + ")").c_str());
    }
    const int layer = static_cast<int>(found - names.begin());
    if (on != "input" && on != "intrinsic")
      throw nb::value_error(("on: '" + on + "' is not input or intrinsic").c_str());
    const size_t input = static_cast<size_t>(session.surface().input.vertex_count());
    const size_t intrinsic = static_cast<size_t>(session.surface_now().domain.vertex_count);
    const bool surface_changed = &session.surface_now() != &session.surface();  // a growing sheet
    if (on == "input" && surface_changed && intrinsic != input)
      throw nb::value_error(("set_field: the growing sheet has been refined since the start (" + std::to_string(intrinsic) +
                             " vertices now, the input has " + std::to_string(input) +
                             "): give values per sheet vertex with on=\"intrinsic\"")
                                .c_str());
    const size_t expected = on == "input" ? input : intrinsic;
    if (values.size() != expected)
      throw nb::value_error(("set_field: " + std::to_string(values.size()) + " values for '" + name + "', expected " +
                             std::to_string(expected) + " (one per " + (on == "input" ? "input" : "intrinsic") + " vertex)")
                                .c_str());
    nb::gil_scoped_release unlocked;
    if (on == "input") session.set_field_on_input(InputVertexData<double>(std::move(values)), layer);
    else session.set_field(IntrinsicVertexData<double>(std::move(values)), layer);
  }

  // A growth run's sheet now: its vertices (deformed), its triangles and its fields per vertex (every
  // morphogen, "area_growth"); None for another model.
  nb::object sheet() {
    const GrowthSimulation* growth = run_->session().growth();
    if (!growth) return nb::none();
    const Session& session = run_->session();
    const InputMesh& mesh = growth->surface().input;
    nb::dict fields;
    for (int layer = 0; layer < static_cast<int>(session.layer_names().size()); ++layer)
      fields[session.layer_names()[static_cast<size_t>(layer)].c_str()] = to_numpy(std::move(growth->field_values(layer).values()));
    fields["area_growth"] = to_numpy(std::move(growth->area_growth().values()));
    const nb::tuple arrays = mesh_arrays(mesh);
    return nb::make_tuple(arrays[0], arrays[1], fields);
  }

  // The pattern analysis of a layer now (`physarum analyze`'s analysis.json), on the full-resolution
  // mesh of the surface (a growth run's: its sheet now), as the command reads it from fields_full.ply.
  std::string analyze(const std::string& field, std::optional<double> threshold, bool below, double min_area) {
    Session& session = run_->session();
    const std::vector<std::string>& names = session.layer_names();
    const std::string name = field.empty() ? names[static_cast<size_t>(session.preview_layer())] : field;
    const auto found = std::find(names.begin(), names.end(), name);
    if (found == names.end()) throw nb::value_error(("analyze: no layer '" + name + "'").c_str());
    nb::gil_scoped_release unlocked;
    session.backend().finish();
    const PreparedSurface& surface = session.surface_now();
    const FullResolutionMesh full = build_full_resolution_mesh(surface.input, surface.domain);
    const IntrinsicVertexData<double> values = session.field(static_cast<int>(found - names.begin()));
    return analyze_field(full.mesh, full.vertex_values(values), name, analysis_request(field, threshold, below, min_area))
        .json.dump();
  }

  // stats.csv's columns now: the row the run loop would take at this step.
  nb::dict stats() {
    const ModelRun& model = run_->model();
    std::string row;
    {
      nb::gil_scoped_release unlocked;
      run_->session().backend().finish();
      row = model.stats_row();
    }
    nb::dict out;
    std::istringstream names(model.stats_header), values(row);
    std::string name, value;
    while (std::getline(names, name, ',') && std::getline(values, value, ',')) out[name.c_str()] = std::stod(value);
    return out;
  }

  nb::bytes save_state() {
    std::string bytes;
    {
      nb::gil_scoped_release unlocked;
      bytes = run_->loop().save_state();
    }
    return nb::bytes(bytes.data(), bytes.size());
  }

  void restore_state(const nb::bytes& state) {
    const std::string bytes(state.c_str(), state.size());
    nb::gil_scoped_release unlocked;
    run_->loop().restore_state(bytes, "state");
  }

  // The closing line (to the run's log) and why the run stopped early, if it did.
  std::optional<std::string> write(const std::string& out) {
    RunWritten written;
    {
      nb::gil_scoped_release unlocked;
      written = run_->loop().write(out);
    }
    if (run_->options().log) run_->options().log(written.summary);
    return written.stopped;
  }

  PreparedRun& run() { return *run_; }

 private:
  std::unique_ptr<PreparedRun> run_;
};

}  // namespace

void bind_simulation(nb::module_& m) {
  m.def(
      "_check_scene",
      [](const std::string& scene_file, const std::string& scene_json) {
        if (scene_file.empty()) scene_from_json(nlohmann::json::parse(scene_json), "scene");
        else load_scene(scene_file);
      },
      nb::arg("scene_file"), nb::arg("scene_json"));
  nb::class_<PythonSimulation>(m, "_Simulation")
      .def(nb::init<const std::string&, const std::string&, const std::string&, const std::string&,
                    std::optional<std::uint32_t>, std::optional<long long>, nb::object>(),
           nb::arg("scene_file"), nb::arg("scene_json"), nb::arg("backend"), nb::arg("device"), nb::arg("seed").none(),
           nb::arg("steps").none(), nb::arg("log").none())
      .def("step", &PythonSimulation::step, nb::arg("n"), nb::arg("progress").none())
      .def("fields", &PythonSimulation::fields, nb::arg("on"))
      .def("set_field", &PythonSimulation::set_field, nb::arg("name"), nb::arg("values"), nb::arg("on"))
      .def("sheet", &PythonSimulation::sheet)
      .def(
          "set",
          [](PythonSimulation& s, const std::string& key, const std::string& value_json) {
            nb::gil_scoped_release unlocked;  // a changed backend is built (an OpenCL one's buffers)
            return s.run().session().set(key, nlohmann::json::parse(value_json));
          },
          nb::arg("key"), nb::arg("value_json"))
      .def("analyze", &PythonSimulation::analyze, nb::arg("field"), nb::arg("threshold").none(), nb::arg("below"),
           nb::arg("min_area"))
      .def("stats", &PythonSimulation::stats)
      .def("statistics_text", [](PythonSimulation& s) { return s.run().loop().statistics(); })
      .def("save_state", &PythonSimulation::save_state)
      .def("restore_state", &PythonSimulation::restore_state, nb::arg("state"))
      .def("write", &PythonSimulation::write, nb::arg("out"))
      .def_prop_ro("time", [](PythonSimulation& s) { return s.run().session().backend().time(); })
      .def_prop_ro("steps_taken", [](PythonSimulation& s) { return s.run().loop().steps_taken(); })
      .def_prop_ro("planned_steps", [](PythonSimulation& s) { return s.run().loop().planned_steps(); })
      .def_prop_ro("layer_names", [](PythonSimulation& s) { return s.run().session().layer_names(); })
      .def_prop_ro("backend", [](PythonSimulation& s) { return s.run().session().backend().backend_name(); })
      .def_prop_ro("device", [](PythonSimulation& s) { return s.run().session().backend().device_name(); })
      .def_prop_ro("stopped", [](PythonSimulation& s) -> std::optional<std::string> {
        const ModelRun& model = s.run().model();
        return model.stopped ? model.stopped() : std::nullopt;
      })
      .def_prop_ro("intrinsic_vertex_count",
                   [](PythonSimulation& s) { return s.run().session().surface().domain.vertex_count; });
}

}  // namespace physarum::python
