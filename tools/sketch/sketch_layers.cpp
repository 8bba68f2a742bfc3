#include "tools/sketch/sketch_layers.hpp"

#include "common/pattern/pattern_segmentation.hpp"
#include "common/sketch/median.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum::cli {
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
  // The frozen set's rim (frozen vertices with a free neighbour): the nearest frozen vertex to a free
  // point is on it.
  std::vector<Eigen::Vector3d> rim;
  for (size_t v = 0; v < frozen.size(); ++v)
    if (frozen[v] && std::any_of(neighbours[v].begin(), neighbours[v].end(), [&](int n) { return !frozen[static_cast<size_t>(n)]; }))
      rim.push_back(mesh.positions[v]);
  auto nearest = [&](const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& q : rim) best = std::min(best, (p - q).squaredNorm());
    return std::sqrt(best) * scale;
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
    if (!rim.empty()) m.spot_distance.push_back(nearest(region.mean_position()));
  }
  if (!rim.empty())
    for (size_t v = 0; v < frozen.size(); ++v)
      if (!frozen[v]) m.free_distance.push_back(nearest(mesh.positions[v]));
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
  return {{"mode", rosettes ? "rosettes" : "cascade"},
          {"frozen_spots", m.frozen_spots},
          {"spots", m.spots},
          {"overlapping", m.overlapping},
          {"spot_distance_median_m", spot_median},
          {"free_distance_median_m", free_median},
          {"distance_histogram", {{"bin_starts_m", starts}, {"spots", histogram(m.spot_distance)}, {"free_share", free_share}}},
          // A cascade's new spots stand clear of the frozen ones; rosettes' hug the reset discs: their
          // median distance below the free vertices'.
          {"verdict", (rosettes ? spot_median < free_median : m.overlapping == 0) ? "pass" : "miss"}};
}

}  // namespace physarum::cli
