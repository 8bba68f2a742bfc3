// read_mesh and _Surface: a mesh loaded (and repaired) as `physarum` loads it, prepared into its
// intrinsic triangulation as a run prepares it, and the scene's map tools evaluated on it in-process
// (geodesic distance, Laplace interpolation, diffusion, gradient, elevation: physarum/__init__.py
// writes each as the map JSON a scene would hold, so a result equals `physarum map`'s).
#include "common/maps/map_definition.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/mesh/mesh_repair.hpp"
#include "common/surface/eigenvalues.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/surface/prepared_surface.hpp"
#include "tools/python/bindings.hpp"
#include "tools/python/numpy_arrays.hpp"

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>
#include <nlohmann/json.hpp>

namespace physarum::python {

namespace {

// A prepared surface and its full-resolution mesh (built once, when first asked for).
class PythonSurface {
 public:
  PythonSurface(const std::string& mesh, std::optional<double> scale_to_area, std::optional<double> max_circumradius,
                double min_angle) {
    SurfaceSpec spec{mesh, scale_to_area, max_circumradius, min_angle};
    nb::gil_scoped_release unlocked;  // refinement can take seconds
    surface_ = prepare_surface(spec);
  }

  // A mesh given as arrays (checked by the caller: shapes, dtypes, finite, indices in range), through
  // the repair a file's polygons go through, at full double precision.
  PythonSurface(const nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig>& V,
                const nb::ndarray<const std::int64_t, nb::shape<-1, 3>, nb::c_contig>& F,
                std::optional<double> scale_to_area, std::optional<double> max_circumradius, double min_angle) {
    PolygonSoup soup;
    for (size_t v = 0; v < V.shape(0); ++v) soup.positions.emplace_back(V(v, 0), V(v, 1), V(v, 2));
    for (size_t f = 0; f < F.shape(0); ++f) {
      for (int c = 0; c < 3; ++c) soup.corner_vertex.push_back(static_cast<int>(F(f, c)));
      soup.polygon_start.push_back(static_cast<int>(soup.corner_vertex.size()));
    }
    SurfaceSpec spec{"the arrays V, F", scale_to_area, max_circumradius, min_angle};
    nb::gil_scoped_release unlocked;
    surface_ = prepare_surface(repair_polygon_soup(soup, spec.mesh), spec);
  }

  const PreparedSurface& surface() const { return surface_; }

  const FullResolutionMesh& full() {
    if (!full_) full_ = build_full_resolution_mesh(surface_.input, surface_.domain);
    return *full_;
  }

  // Every map of `maps` (a scene's "maps" object as JSON text; relative files against `folder`):
  // scalar maps per input vertex (on_input) or per intrinsic vertex, vector maps per input face in
  // input coordinates, (m, 3).
  nb::dict evaluate(const std::string& maps_json, const std::string& folder, bool on_input) {
    const MapSet maps = parse_maps(nlohmann::json::parse(maps_json), folder, "maps");
    EvaluatedMaps evaluated;
    {
      nb::gil_scoped_release unlocked;
      evaluated = evaluate_maps(maps, surface_, "maps");
    }
    nb::dict out;
    if (!on_input) {
      for (auto& [name, values] : evaluated.scalar) out[name.c_str()] = to_numpy(std::move(values.values()));
      return out;
    }
    InputMaps written = maps_on_input(maps, surface_, evaluated, "maps");
    for (auto& [name, values] : written.scalar) out[name.c_str()] = to_numpy(std::move(values.values()));
    for (auto& [name, vectors] : written.vector) {
      std::vector<double> flat;
      flat.reserve(3 * vectors.size());
      for (const auto& v : vectors) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      out[name.c_str()] = to_numpy(std::move(flat), 3);
    }
    return out;
  }

 private:
  PreparedSurface surface_;
  std::optional<FullResolutionMesh> full_;
};

}  // namespace

void bind_surface(nb::module_& m) {
  m.def(
      "read_mesh", [](const std::string& path) { return mesh_arrays(load_mesh(path)); }, nb::arg("path"),
      "The mesh in `path` (OBJ, PLY, OFF, STL, ...) or a built-in shape ('shape:sphere'), as loaded and repaired by "
      "physarum: (V, F), V (n, 3) float64, F (m, 3) int64.");

  nb::class_<PythonSurface>(m, "_Surface")
      .def(nb::init<const std::string&, std::optional<double>, std::optional<double>, double>(), nb::arg("mesh"),
           nb::arg("scale_to_area").none(), nb::arg("max_circumradius").none(), nb::arg("min_angle"))
      .def(nb::init<const nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig>&,
                    const nb::ndarray<const std::int64_t, nb::shape<-1, 3>, nb::c_contig>&, std::optional<double>,
                    std::optional<double>, double>(),
           nb::arg("V"), nb::arg("F"), nb::arg("scale_to_area").none(), nb::arg("max_circumradius").none(),
           nb::arg("min_angle"))
      .def_prop_ro("input_vertex_count", [](const PythonSurface& s) { return s.surface().input.vertex_count(); })
      .def_prop_ro("input_face_count", [](const PythonSurface& s) { return s.surface().input.triangle_count(); })
      .def_prop_ro("vertex_count", [](const PythonSurface& s) { return s.surface().domain.vertex_count; })
      .def_prop_ro("face_count", [](const PythonSurface& s) { return s.surface().domain.face_count; })
      .def_prop_ro("area", [](const PythonSurface& s) { return s.surface().domain.total_area; })
      .def_prop_ro("diameter", [](const PythonSurface& s) { return s.surface().diameter; })
      .def_prop_ro("warnings", [](const PythonSurface& s) { return s.surface().warnings; })
      .def("input_mesh", [](const PythonSurface& s) { return mesh_arrays(s.surface().input); })
      .def("full_mesh", [](PythonSurface& s) { return mesh_arrays(s.full().mesh); })
      .def("input_to_intrinsic",
           [](const PythonSurface& s) {
             const auto& map = s.surface().input_to_intrinsic;
             return to_numpy(std::vector<std::int64_t>(map.begin(), map.end()), 1);
           })
      .def("vertex_mass", [](const PythonSurface& s) { return to_numpy(std::vector<double>(s.surface().domain.vertex_mass.values())); })
      .def(
          "eigenvalues",
          [](const PythonSurface& s, int count) {
            if (count < 1) throw nb::value_error("count: must be >= 1");
            std::vector<double> values;
            {
              nb::gil_scoped_release unlocked;
              values = smallest_eigenvalues(s.surface().domain, count);
            }
            return to_numpy(std::move(values));
          },
          nb::arg("count"))
      .def("evaluate_maps", &PythonSurface::evaluate, nb::arg("maps_json"), nb::arg("folder"), nb::arg("on_input"));
}

}  // namespace physarum::python
