// Neighbouring spots (touching geodesic Voronoi cells) and their geodesic distances.
#include "common/pattern/spot_spacing.hpp"

#include "common/map_tools/fast_marching.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

namespace physarum {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<size_t>(v)] != v) {
    parent[static_cast<size_t>(v)] = parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
    v = parent[static_cast<size_t>(v)];
  }
  return v;
}

// The pairs among `spots` (indices into all_spots) on one piece of the surface, given as its own mesh
// with `local` mapping the full mesh's vertex ids to the piece's (-1 elsewhere).
void pairs_on_piece(const InputMesh& piece, const std::vector<int>& local, const InputMesh& mesh,
                    const std::vector<SpotShape>& all_spots, const std::vector<int>& spots, std::vector<SpotPair>& out) {
  const IntrinsicMesh intrinsic = intrinsic_mesh_from_input(piece);
  const SurfaceDomain domain = build_surface_domain(intrinsic);
  const FastMarchingGeodesics fmm(domain);
  const size_t n = static_cast<size_t>(piece.vertex_count());

  // Voronoi labels from one multi-source run.
  std::vector<int> seeds;
  std::vector<int> label(n, -1);
  for (int s : spots) {
    const int v = local[static_cast<size_t>(all_spots[static_cast<size_t>(s)].centre_vertex)];
    if (label[static_cast<size_t>(v)] < 0) {  // two tiny spots sharing a start vertex: the first keeps it
      label[static_cast<size_t>(v)] = s;
      seeds.push_back(v);
    }
  }
  const IntrinsicVertexData<double> nearest = fmm.distance(seeds);
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& t : piece.triangles)
    for (int k = 0; k < 3; ++k) {
      neighbours[static_cast<size_t>(t[static_cast<size_t>(k)])].push_back(t[static_cast<size_t>((k + 1) % 3)]);
      neighbours[static_cast<size_t>(t[static_cast<size_t>((k + 1) % 3)])].push_back(t[static_cast<size_t>(k)]);
    }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return nearest[static_cast<size_t>(x)] < nearest[static_cast<size_t>(y)]; });
  for (int v : order) {
    if (label[static_cast<size_t>(v)] >= 0) continue;
    int from = -1;
    for (int w : neighbours[static_cast<size_t>(v)])
      if (label[static_cast<size_t>(w)] >= 0 && (from < 0 || nearest[static_cast<size_t>(w)] < nearest[static_cast<size_t>(from)]))
        from = w;
    // Every vertex but a seed has a neighbour accepted before it (the piece is connected).
    label[static_cast<size_t>(v)] = from >= 0 ? label[static_cast<size_t>(from)] : spots.front();
  }
  std::set<std::pair<int, int>> touching;
  for (size_t v = 0; v < n; ++v)
    for (int w : neighbours[v])
      if (label[v] != label[static_cast<size_t>(w)])
        touching.emplace(std::min(label[v], label[static_cast<size_t>(w)]), std::max(label[v], label[static_cast<size_t>(w)]));

  // Distances: fast marching from each spot over its own cell and its neighbours' cells only (the
  // triangles with a corner in them), which holds the geodesic to every neighbour that runs through
  // their shared border, and keeps the cost near a few whole-surface runs instead of one per spot.
  std::map<int, std::vector<int>> adjacent;
  for (const auto& [a, b] : touching) {
    adjacent[a].push_back(b);
    adjacent[b].push_back(a);
  }
  std::map<std::pair<int, int>, double> one_way;  // (from, to): from's centre to to's centre
  for (const auto& [s, others] : adjacent) {
    std::set<int> cells(others.begin(), others.end());
    cells.insert(s);
    InputMesh window;
    window.source = piece.source;
    std::vector<int> window_id(n, -1);
    for (const auto& t : piece.triangles) {
      bool inside = false;
      for (int c : t) inside = inside || cells.count(label[static_cast<size_t>(c)]) > 0;
      if (!inside) continue;
      std::array<int, 3> corners{};
      for (int k = 0; k < 3; ++k) {
        int& id = window_id[static_cast<size_t>(t[static_cast<size_t>(k)])];
        if (id < 0) {
          id = window.vertex_count();
          window.positions.push_back(piece.positions[static_cast<size_t>(t[static_cast<size_t>(k)])]);
          window.file_vertex.push_back(t[static_cast<size_t>(k)]);
        }
        corners[static_cast<size_t>(k)] = id;
      }
      window.triangles.push_back(corners);
    }
    const IntrinsicMesh window_intrinsic = intrinsic_mesh_from_input(window);
    const SurfaceDomain window_domain = build_surface_domain(window_intrinsic);
    const FastMarchingGeodesics window_fmm(window_domain);
    const int source = window_id[static_cast<size_t>(local[static_cast<size_t>(all_spots[static_cast<size_t>(s)].centre_vertex)])];
    const IntrinsicVertexData<double> d = window_fmm.distance({source});
    for (int b : others) {
      // The other centre, interpolated in its triangle. Its corners all lie in the window: one of
      // them is b's start vertex, which carries b's label (b has a cell, or it would touch nothing).
      const SpotShape& spot = all_spots[static_cast<size_t>(b)];
      const auto& t = mesh.triangles[static_cast<size_t>(spot.centre_face)];
      double value = 0.0;
      for (int k = 0; k < 3; ++k) {
        const int id = window_id[static_cast<size_t>(local[static_cast<size_t>(t[static_cast<size_t>(k)])])];
        if (id < 0) throw std::logic_error("spot spacing: a neighbour's centre triangle lies outside the window");
        value += spot.centre_barycentric[k] * d[static_cast<size_t>(id)];
      }
      one_way[{s, b}] = value;
    }
  }
  for (const auto& [a, b] : touching) out.push_back({a, b, 0.5 * (one_way.at({a, b}) + one_way.at({b, a}))});
}

}  // namespace

std::vector<SpotPair> neighbouring_spot_pairs(const InputMesh& mesh, const std::vector<SpotShape>& spots) {
  // Pieces of the surface: components of the triangles' vertex graph.
  const size_t n = static_cast<size_t>(mesh.vertex_count());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) parent[static_cast<size_t>(find_root(parent, t[0]))] = find_root(parent, t[static_cast<size_t>(k)]);
  std::map<int, std::vector<int>> spots_by_piece;
  for (size_t s = 0; s < spots.size(); ++s)
    spots_by_piece[find_root(parent, spots[s].centre_vertex)].push_back(static_cast<int>(s));

  std::vector<SpotPair> pairs;
  for (const auto& [root, piece_spots] : spots_by_piece) {
    if (piece_spots.size() < 2) continue;
    InputMesh piece;
    piece.source = mesh.source;
    std::vector<int> local(n, -1);
    for (size_t v = 0; v < n; ++v)
      if (find_root(parent, static_cast<int>(v)) == root) {
        local[v] = piece.vertex_count();
        piece.positions.push_back(mesh.positions[v]);
        piece.file_vertex.push_back(static_cast<int>(v));
      }
    for (const auto& t : mesh.triangles)
      if (local[static_cast<size_t>(t[0])] >= 0)
        piece.triangles.push_back({local[static_cast<size_t>(t[0])], local[static_cast<size_t>(t[1])], local[static_cast<size_t>(t[2])]});
    pairs_on_piece(piece, local, mesh, spots, piece_spots, pairs);
  }
  std::sort(pairs.begin(), pairs.end(), [](const SpotPair& x, const SpotPair& y) { return std::pair(x.a, x.b) < std::pair(y.a, y.b); });
  return pairs;
}

}  // namespace physarum
