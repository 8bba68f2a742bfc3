// `physarum mesh MESH ...`: load, repair and validate a surface, build its intrinsic Delaunay
// triangulation (optionally refined), and report statistics and Laplace eigenvalues.
#include "common/surface/eigenvalues.hpp"
#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_triangulation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/surface/surface_domain.hpp"
#include "tools/commands.hpp"
#include "tools/refinement_options.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>

namespace physarum::cli {
namespace {

struct MeshOptions {
  std::string mesh;
  RefinementFlags refinement;
  int eigenvalues = 0;
  size_t max_insertions = 10'000'000;
  bool json = false;
};

int run_mesh(const MeshOptions& o) {
  const InputMesh input = load_mesh(o.mesh);
  for (const std::string& w : input.warnings) std::cerr << "physarum: warning: " << input.source << ": " << w << "\n";
  const InputMeshStatistics in = compute_statistics(input);

  const auto t0 = std::chrono::steady_clock::now();
  IntrinsicTriangulation triangulation(input);
  triangulation.flip_to_delaunay();
  RefinementOptions refinement;
  refinement.max_circumradius =
      o.refinement.absolute_max_circumradius(in.bounding_box_diagonal).value_or(std::numeric_limits<double>::infinity());
  refinement.min_angle_deg = o.refinement.min_angle_deg;
  refinement.max_insertions = o.max_insertions;
  if (o.refinement.any()) triangulation.refine(refinement);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<double> lambda;
  if (o.eigenvalues > 0) {
    const SurfaceDomain domain = build_surface_domain(triangulation.snapshot());
    lambda = smallest_eigenvalues(domain, o.eigenvalues);
  }

  nlohmann::ordered_json j;
  j["mesh"] = input.source;
  j["input"] = {{"vertices", in.vertices},
                {"faces", in.faces},
                {"edges", in.edges},
                {"components", in.components},
                {"genus", in.genus},
                {"boundary_loops", in.boundary_loops},
                {"area", in.area},
                {"bounding_box_diagonal", in.bounding_box_diagonal},
                {"split_vertices", input.split_vertices},
                {"dropped_unreferenced", input.dropped_unreferenced},
                {"triangulated_polygons", input.triangulated_polygons}};
  j["intrinsic"] = {{"vertices", triangulation.vertex_count()},
                    {"faces", triangulation.face_count()},
                    {"delaunay", triangulation.is_delaunay()},
                    {"min_angle_deg", triangulation.min_angle_deg()},
                    {"max_circumradius", triangulation.max_circumradius()},
                    {"flips", triangulation.flip_count()},
                    {"insertions", triangulation.insertion_count()},
                    {"seconds", seconds}};
  j["eigenvalues"] = lambda;

  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::printf("mesh            %s\n", input.source.c_str());
  std::printf("input           V %d  F %d  E %d  components %d  genus %d  boundary loops %d  area %.6g\n",
              in.vertices, in.faces, in.edges, in.components, in.genus, in.boundary_loops, in.area);
  std::printf("intrinsic       V %d  F %d  Delaunay %s  min angle %.3f deg  max circumradius %.6g\n",
              triangulation.vertex_count(), triangulation.face_count(), triangulation.is_delaunay() ? "yes" : "no",
              triangulation.min_angle_deg(), triangulation.max_circumradius());
  std::printf("                flips %zu  insertions %zu  %.3f s\n", triangulation.flip_count(),
              triangulation.insertion_count(), seconds);
  if (!lambda.empty()) {
    std::printf("eigenvalues     ");
    for (size_t i = 0; i < lambda.size(); ++i) std::printf("%s%.9g", i ? " " : "", lambda[i]);
    std::printf("\n");
  }
  return 0;
}

}  // namespace

Command add_mesh_command(CLI::App& parent) {
  auto options = std::make_shared<MeshOptions>();
  CLI::App* app = parent.add_subcommand("mesh", "Input and intrinsic-triangulation statistics of a surface");
  app->add_option("MESH", options->mesh,
                  "Mesh file (OBJ, OFF, PLY, STL) or a built-in surface shape:NAME (square, disk, sphere, "
                  "skinny-sphere, torus, octagonal-prism)")->required();
  add_refinement_flags(app, options->refinement, "Refine until no intrinsic face has a larger circumradius (input units)");
  app->add_option("--max-insertions", options->max_insertions, "Budget of vertex insertions during refinement")
      ->check(CLI::PositiveNumber);
  app->add_option("--eigenvalues", options->eigenvalues, "Print the K smallest eigenvalues of L x = lambda M x")
      ->check(CLI::NonNegativeNumber);
  app->add_flag("--json", options->json, "Machine-readable output");
  return {app, [options] { return run_mesh(*options); }};
}

}  // namespace physarum::cli
