#include "common/setup/growing_sheet_surface.hpp"

#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/scene/scene_fields.hpp"
#include "common/shell/membrane_energy.hpp"
#include "common/shell/rest_metric.hpp"

#include <Eigen/LU>

#include <cmath>
#include <unordered_map>

namespace physarum {
namespace {

// The face's edge vectors e1 = corner 1 - corner 0, e2 = corner 2 - corner 0 in its 2D frame.
Eigen::Matrix2d frame_edges(const SurfaceDomain& domain, int f) {
  const auto& c = domain.face_corners[static_cast<size_t>(f)];
  Eigen::Matrix2d edges;
  edges.col(0) = c[1] - c[0];
  edges.col(1) = c[2] - c[0];
  return edges;
}

}  // namespace

InputMesh sheet_mesh(const GrowingSheet& sheet, const std::string& source) {
  InputMesh mesh;
  mesh.source = source;
  mesh.positions = sheet.positions;
  mesh.triangles = sheet.topology.faces;
  mesh.file_vertex.resize(sheet.positions.size());
  for (size_t i = 0; i < sheet.positions.size(); ++i) mesh.file_vertex[i] = static_cast<int>(i);
  return mesh;
}

PreparedSurface sheet_surface(const GrowingSheet& sheet, const std::string& source) {
  PreparedSurface s;
  s.input = sheet_mesh(sheet, source);
  s.simulated = s.input;
  s.diameter = compute_statistics(s.simulated).bounding_box_diagonal;
  IntrinsicMesh intrinsic = intrinsic_mesh_from_input(s.simulated);
  // Halfedge 3f+i runs from corner i to corner i+1: the edge opposite corner (i+2) % 3.
  std::vector<std::array<double, 3>> squared(sheet.topology.faces.size());
  for (size_t f = 0; f < squared.size(); ++f)
    for (int i = 0; i < 3; ++i) squared[f][i] = rest_edge_length_squared(sheet.rest.face_metric[f], (i + 2) % 3);
  for (size_t f = 0; f < squared.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int twin = intrinsic.twin[f][i];
      const double mean = twin < 0 ? squared[f][i] : 0.5 * (squared[f][i] + squared[static_cast<size_t>(twin / 3)][twin % 3]);
      intrinsic.edge_lengths[f][i] = std::sqrt(mean);
    }
    const auto& l = intrinsic.edge_lengths[f];
    if (!(l[0] < l[1] + l[2] && l[1] < l[2] + l[0] && l[2] < l[0] + l[1]))
      throw InputError(source + ": the rest lengths of face " + std::to_string(f) +
                       " no longer form a triangle (neighbouring faces grew too differently in one step: a smaller "
                       "growth rate or more growth steps)");
  }
  s.domain = build_surface_domain(intrinsic);
  s.input_to_intrinsic = InputVertexData<int>(static_cast<size_t>(s.input.vertex_count()));
  for (int i = 0; i < s.input.vertex_count(); ++i) s.input_to_intrinsic[static_cast<size_t>(i)] = i;
  return s;
}

GrowingSheet initial_sheet(const Scene& scene) {
  if (scene.max_circumradius || scene.min_angle_deg > 0.0)
    fail_key(scene.source, scene.max_circumradius ? "max_circumradius" : "min_angle",
             "a growth scene simulates on its mesh's own triangles (the shell's); refine the growing sheet with "
             "\"refine\": {\"max_edge\": L}, or start from a finer mesh (shape:disk-55 has 9,241 vertices)");
  InputMesh mesh = load_mesh(scene.mesh);
  if (scene.scale_to_area) {
    const double area = compute_statistics(mesh).area;
    if (!(area > 0.0)) throw InputError(mesh.source + ": surface area " + std::to_string(area) + " cannot be scaled");
    const double factor = std::sqrt(*scene.scale_to_area / area);
    for (Eigen::Vector3d& p : mesh.positions) p *= factor;
  }
  return sheet_at_rest(mesh);
}

GrowingSheet sheet_at_rest(const InputMesh& mesh) {
  GrowingSheet sheet;
  sheet.topology = build_shell_topology(mesh.vertex_count(), mesh.triangles);
  sheet.positions = mesh.positions;
  sheet.rest = rest_state_of(sheet.topology, sheet.positions);
  for (const Eigen::Matrix2d& metric : sheet.rest.face_metric) sheet.initial_area.push_back(metric_area(metric));
  return sheet;
}

SheetMapLayout carry_maps(GrowingSheet& sheet, const EvaluatedMaps& maps, const SurfaceDomain& domain) {
  SheetMapLayout layout;
  layout.first_value = static_cast<int>(sheet.values.size());
  for (const auto& [name, values] : maps.scalar) {
    layout.scalar.push_back(name);
    sheet.values.emplace_back(values.begin(), values.end());
  }
  for (const auto& [name, vectors] : maps.vector) {
    layout.vector.push_back(name);
    std::vector<Eigen::Vector2d> coefficients(vectors.size());
    for (size_t f = 0; f < vectors.size(); ++f)
      coefficients[f] = frame_edges(domain, static_cast<int>(f)).inverse() * Eigen::Vector2d(vectors[f][0], vectors[f][1]);
    sheet.directions.push_back(std::move(coefficients));
  }
  return layout;
}

EvaluatedMaps sheet_maps(const GrowingSheet& sheet, const SheetMapLayout& layout, const SurfaceDomain& domain) {
  EvaluatedMaps maps;
  for (size_t k = 0; k < layout.scalar.size(); ++k) {
    const std::vector<double>& values = sheet.values[static_cast<size_t>(layout.first_value) + k];
    maps.scalar[layout.scalar[k]] = IntrinsicVertexData<double>(values);
  }
  for (size_t k = 0; k < layout.vector.size(); ++k) {
    const std::vector<Eigen::Vector2d>& coefficients = sheet.directions[k];
    IntrinsicFaceData<std::array<double, 2>> vectors(coefficients.size());
    for (size_t f = 0; f < coefficients.size(); ++f) {
      const Eigen::Vector2d d = frame_edges(domain, static_cast<int>(f)) * coefficients[f];
      vectors[f] = {d.x(), d.y()};
    }
    maps.vector[layout.vector[k]] = std::move(vectors);
  }
  return maps;
}

}  // namespace physarum
