#include "api/sketch/sketch_layers.hpp"

#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/map_tools/fast_marching.hpp"
#include "common/pattern/pattern_segmentation.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/sketch/median.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {

// Each vertex's neighbours along the triangles' edges.
std::vector<std::vector<int>> vertex_neighbours(const InputMesh& mesh) {
  std::vector<std::vector<int>> neighbours(mesh.positions.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      neighbours[static_cast<size_t>(a)].push_back(b);
      neighbours[static_cast<size_t>(b)].push_back(a);
    }
  return neighbours;
}

// Connected sets of frozen vertices (breadth first along the edges).
int frozen_components(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& frozen) {
  std::vector<char> seen(frozen.size(), 0);
  int count = 0;
  for (size_t start = 0; start < frozen.size(); ++start) {
    if (!frozen[start] || seen[start]) continue;
    ++count;
    std::vector<int> queue = {static_cast<int>(start)};
    seen[start] = 1;
    while (!queue.empty()) {
      const int v = queue.back();
      queue.pop_back();
      for (const int n : neighbours[static_cast<size_t>(v)])
        if (frozen[static_cast<size_t>(n)] && !seen[static_cast<size_t>(n)]) seen[static_cast<size_t>(n)] = 1, queue.push_back(n);
    }
  }
  return count;
}

}  // namespace

void make_cascade_scene(nlohmann::ordered_json& scene, const ReactionModel& model, const std::string& field,
                        const Cascade& cascade) {
  nlohmann::ordered_json uniform = nlohmann::ordered_json::object();
  for (size_t m = 0; m < model.morphogens.size(); ++m) {
    const std::string& name = model.morphogens[m];
    scene["maps"]["first_" + name] = {{"fields_full", cascade.first_fields}, {"property", name}};
    scene["morphogens"][name]["initial"] = "first_" + name;
    uniform[name] = model.initial[m];
  }
  scene["maps"]["frozen"] = {{"threshold", "first_" + field}, {"at", cascade.threshold}};
  scene["dirichlet"] = {{"map", "frozen"}};
  if (cascade.rosettes) scene["dirichlet"]["values"] = uniform;
}

std::vector<char> frozen_vertices(const std::vector<double>& first_field, double threshold) {
  std::vector<char> frozen;
  for (const double x : first_field) frozen.push_back(x >= threshold ? 1 : 0);
  return frozen;
}

CascadeMeasure measure_cascade(const InputMesh& mesh, const std::vector<double>& field, double threshold,
                               const std::vector<char>& frozen, double scale) {
  CascadeMeasure m;
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(mesh);
  m.frozen_spots = frozen_components(neighbours, frozen);
  // The distance along the surface to the frozen set: fast marching from its rim (frozen vertices
  // with a free neighbour), in the mesh's units. A piece of the surface without frozen spots has no
  // distance: its spots and vertices are left out of the histogram.
  std::vector<int> rim;
  for (size_t v = 0; v < frozen.size(); ++v)
    if (frozen[v] && std::any_of(neighbours[v].begin(), neighbours[v].end(), [&](int n) { return !frozen[static_cast<size_t>(n)]; }))
      rim.push_back(static_cast<int>(v));
  std::vector<double> distance(frozen.size(), std::numeric_limits<double>::quiet_NaN());
  if (!rim.empty()) {
    try {
      const SurfaceDomain domain = build_surface_domain(intrinsic_mesh_from_input(mesh));
      const IntrinsicVertexData<double> d = FastMarchingGeodesics(domain).distance(rim);
      for (size_t v = 0; v < distance.size(); ++v) distance[v] = d[v] * scale;
    } catch (const InputError&) {
      // A piece no frozen spot lies on: the distances stay unknown.
    }
  }
  // A spot's distance: its vertex nearest its centre's.
  auto centre_distance = [&](const PatternRegion& region) {
    const Eigen::Vector3d centre = region.mean_position();
    int best = region.vertices.front();
    for (const int v : region.vertices)
      if ((mesh.positions[static_cast<size_t>(v)] - centre).squaredNorm() <
          (mesh.positions[static_cast<size_t>(best)] - centre).squaredNorm())
        best = v;
    return distance[static_cast<size_t>(best)];
  };
  auto is_peak = [&](int v) {
    const auto& n = neighbours[static_cast<size_t>(v)];
    return !frozen[static_cast<size_t>(v)] &&
           std::all_of(n.begin(), n.end(), [&](int w) { return field[static_cast<size_t>(v)] > field[static_cast<size_t>(w)]; });
  };
  const PatternSegmentation segmentation = segment_pattern(mesh, InputVertexData<double>(field), threshold);
  for (const PatternRegion& region : segmentation.regions) {
    const bool first_layer = std::any_of(region.vertices.begin(), region.vertices.end(),
                                         [&](int v) { return frozen[static_cast<size_t>(v)] != 0; });
    if (first_layer) {
      m.overlapping += static_cast<int>(std::count_if(region.vertices.begin(), region.vertices.end(), is_peak));
      continue;
    }
    ++m.spots;
    if (const double d = centre_distance(region); std::isfinite(d)) m.spot_distance.push_back(d);
  }
  for (size_t v = 0; v < frozen.size(); ++v)
    if (!frozen[v] && std::isfinite(distance[v])) m.free_distance.push_back(distance[v]);
  return m;
}

nlohmann::ordered_json cascade_json(const CascadeMeasure& m, bool rosettes) {
  // Eight bins of a quarter of the free vertices' median distance, and what lies beyond: the new
  // spots' counts beside the share of the free surface (its vertices) at those distances.
  const double free_median = median(m.free_distance);
  std::vector<double> starts;
  for (int k = 0; k <= 8; ++k) starts.push_back(0.25 * k * free_median);
  auto histogram = [&](const std::vector<double>& distances) {
    std::vector<double> counts(starts.size(), 0.0);
    for (const double d : distances) {
      const auto bin = std::upper_bound(starts.begin(), starts.end(), d) - starts.begin() - 1;
      counts[static_cast<size_t>(std::clamp<std::ptrdiff_t>(bin, 0, static_cast<std::ptrdiff_t>(counts.size()) - 1))] += 1.0;
    }
    return counts;
  };
  std::vector<double> free_share = histogram(m.free_distance);
  for (double& share : free_share) share /= std::max<size_t>(m.free_distance.size(), 1);
  const double spot_median = median(m.spot_distance);
  // Near a frozen spot: within 3/4 of the free surface's median distance (the first three bins).
  auto near_share = [&](const std::vector<double>& distances) {
    const auto near = std::count_if(distances.begin(), distances.end(), [&](double d) { return d < 0.75 * free_median; });
    return distances.empty() ? 0.0 : static_cast<double>(near) / static_cast<double>(distances.size());
  };
  const double near_spots = near_share(m.spot_distance), near_free = near_share(m.free_distance);
  return {{"mode", rosettes ? "rosettes" : "cascade"},
          {"frozen_spots", m.frozen_spots},
          {"spots", m.spots},
          {"overlapping", m.overlapping},
          {"spot_distance_median_m", spot_median},
          {"free_distance_median_m", free_median},
          {"distance_histogram", {{"bin_starts_m", starts}, {"spots", histogram(m.spot_distance)}, {"free_share", free_share}}},
          {"near_share", {{"spots", near_spots}, {"free", near_free}}},
          // A cascade's new spots stand clear of the frozen ones; rosettes' gather round the reset
          // discs: more of them near one than of the free surface.
          {"verdict", (rosettes ? near_spots > near_free : m.overlapping == 0) ? "pass" : "miss"}};
}

}  // namespace physarum
