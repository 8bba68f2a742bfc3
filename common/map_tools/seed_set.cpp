#include "common/map_tools/seed_set.hpp"

#include "common/base/errors.hpp"
#include "common/surface/surface_domain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace physarum {

using nlohmann::json;

std::vector<std::string> SeedSet::map_dependencies() const {
  if (const auto* region = std::get_if<SeedRegion>(&source)) return {region->map};
  return {};
}

SeedSet parse_seed_set(const json& value, const std::string& where) {
  auto fail = [&](const std::string& problem) -> void { throw InputError(where + ": " + problem); };
  const std::string shapes =
      "a scalar map's name (its vertices >= 0.5), {\"points\": [[x, y, z], ...]}, {\"boundary\": true} or "
      "{\"boundary\": {\"spacing\": s}}";
  if (value.is_string()) {
    if (value.get<std::string>().empty()) fail("an empty map name (expected " + shapes + ")");
    return SeedSet{SeedRegion{value.get<std::string>()}};
  }
  if (!value.is_object() || value.size() != 1 || !(value.contains("points") || value.contains("boundary")))
    fail(value.dump() + " is no seed set (expected " + shapes + ")");
  if (value.contains("points")) {
    const json& list = value.at("points");
    if (!list.is_array() || list.empty()) fail("\"points\" = " + list.dump() + " must be a non-empty list of [x, y, z]");
    SeedPoints points;
    for (size_t i = 0; i < list.size(); ++i) {
      const json& p = list[i];
      const bool numbers = p.is_array() && p.size() == 3 && std::all_of(p.begin(), p.end(), [](const json& x) { return x.is_number(); });
      if (!numbers) fail("\"points\"[" + std::to_string(i) + "] = " + p.dump() + " must be three numbers [x, y, z]");
      const Eigen::Vector3d x(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      if (!x.allFinite()) fail("\"points\"[" + std::to_string(i) + "] must be finite");
      points.points.push_back(x);
    }
    return SeedSet{points};
  }
  const json& boundary = value.at("boundary");
  if (boundary.is_boolean() && boundary.get<bool>()) return SeedSet{SeedBoundary{}};
  if (boundary.is_object() && boundary.size() == 1 && boundary.contains("spacing")) {
    const json& spacing = boundary.at("spacing");
    if (!spacing.is_number() || !std::isfinite(spacing.get<double>()) || !(spacing.get<double>() > 0.0))
      fail("\"boundary\": \"spacing\" = " + spacing.dump() + " must be a number > 0 (metres along the boundary, after scale_to_area)");
    return SeedSet{SeedBoundary{spacing.get<double>()}};
  }
  fail("\"boundary\" = " + boundary.dump() + " must be true (every boundary vertex) or {\"spacing\": s} (a seed every s metres)");
  return {};  // not reached
}

std::vector<BoundaryLoop> boundary_loops(const SurfaceDomain& domain) {
  // Boundary halfedges by their start vertex; the surface is on the left of each.
  std::multimap<int, int> leaving;
  for (int f = 0; f < domain.face_count; ++f)
    for (int i = 0; i < 3; ++i)
      if (domain.face_neighbour[f][i] < 0) leaving.emplace(domain.face_vertices[f][i], 3 * f + i);
  std::vector<BoundaryLoop> loops;
  while (!leaving.empty()) {
    BoundaryLoop loop;
    auto it = leaving.begin();
    const int start = it->first;
    for (;;) {
      const int h = it->second, f = h / 3, i = h % 3;
      leaving.erase(it);
      loop.vertices.push_back(domain.face_vertices[f][i]);
      loop.edge_length.push_back((domain.face_corners[f][(i + 1) % 3] - domain.face_corners[f][i]).norm());
      const int end = domain.face_vertices[f][(i + 1) % 3];
      if (end == start) break;
      // At a vertex where the boundary touches itself there are several edges leaving: any one
      // continues a closed loop, and the others are met later as their own loop.
      it = leaving.find(end);
      if (it == leaving.end()) break;  // an open chain (not from a valid domain): keep what was walked
    }
    const auto lowest = std::min_element(loop.vertices.begin(), loop.vertices.end()) - loop.vertices.begin();
    std::rotate(loop.vertices.begin(), loop.vertices.begin() + lowest, loop.vertices.end());
    std::rotate(loop.edge_length.begin(), loop.edge_length.begin() + lowest, loop.edge_length.end());
    loops.push_back(std::move(loop));
  }
  return loops;
}

namespace {

// Vertices every `spacing` along one loop, from its first vertex: the vertex nearest (in arc length)
// to each stipple point.
void stipple(const BoundaryLoop& loop, double spacing, std::vector<int>& out) {
  const size_t n = loop.vertices.size();
  std::vector<double> at(n + 1, 0.0);  // arc length at each vertex; at[n] = the whole loop
  for (size_t i = 0; i < n; ++i) at[i + 1] = at[i] + loop.edge_length[i];
  const double length = at[n];
  for (long long j = 0;; ++j) {
    const double s = static_cast<double>(j) * spacing;
    // The last point must not land on the first again (a loop that is a whole number of spacings).
    if (j > 0 && s >= length * (1.0 - 1e-12)) break;
    const size_t after = static_cast<size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin());
    const size_t hi = std::min(after, n), lo = hi - 1;
    const size_t nearest = (s - at[lo] <= at[hi] - s) ? lo : hi;
    out.push_back(loop.vertices[nearest % n]);
  }
}

}  // namespace

std::vector<int> seed_vertices(const SeedSet& seeds, const SeedSurface& surface, const std::string& where) {
  const SurfaceDomain& domain = surface.domain;
  std::vector<int> out;
  if (const auto* region = std::get_if<SeedRegion>(&seeds.source)) {
    const IntrinsicVertexData<double>& values = surface.scalar_map(region->map);
    double largest = -std::numeric_limits<double>::infinity();
    for (int v = 0; v < domain.vertex_count; ++v) {
      if (values[static_cast<size_t>(v)] >= 0.5) out.push_back(v);
      largest = std::max(largest, values[static_cast<size_t>(v)]);
    }
    if (out.empty())
      throw InputError(where + ": the region '" + region->map + "' holds no intrinsic vertex (a region is where the map is >= 0.5, and '" +
                       region->map + "' is at most " + std::to_string(largest) + "): the seed set is empty");
  } else if (const auto* points = std::get_if<SeedPoints>(&seeds.source)) {
    for (const Eigen::Vector3d& p : points->points) {
      int best = -1;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int v = 0; v < domain.vertex_count; ++v) {
        const double d = (surface.vertex_position[static_cast<size_t>(v)] - p).squaredNorm();
        if (d < best_distance) best_distance = d, best = v;
      }
      if (best < 0) throw InputError(where + ": the surface has no vertex to seed from");
      out.push_back(best);
    }
  } else {
    const auto& boundary = std::get<SeedBoundary>(seeds.source);
    const std::vector<BoundaryLoop> loops = boundary_loops(domain);
    if (loops.empty())
      throw InputError(where + ": boundary seeds on a closed surface (it has no boundary); use \"points\" or a region instead");
    for (const BoundaryLoop& loop : loops) {
      if (boundary.spacing)
        stipple(loop, *boundary.spacing, out);
      else
        out.insert(out.end(), loop.vertices.begin(), loop.vertices.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw InputError(where + ": the seed set is empty");
  return out;
}

}  // namespace physarum
