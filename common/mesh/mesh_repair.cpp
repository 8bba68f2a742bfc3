#include "common/mesh/mesh_repair.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/mesh_polygon_triangulation.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <sstream>

namespace physarum {
namespace {

std::string count_of(int n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

// Halfedges h = 3t + k (from corner k to corner k+1 of triangle t) sorted by undirected edge, so
// the halfedges of one edge are adjacent.
struct EdgeIncidence {
  std::uint64_t key;
  int halfedge;
};

std::vector<EdgeIncidence> sorted_edge_incidences(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<EdgeIncidence> incidences;
  incidences.reserve(triangles.size() * 3);
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) incidences.push_back({undirected_edge_key(triangles[t][k], triangles[t][(k + 1) % 3]), 3 * t + k});
  std::sort(incidences.begin(), incidences.end(),
            [](const EdgeIncidence& a, const EdgeIncidence& b) { return a.key != b.key ? a.key < b.key : a.halfedge < b.halfedge; });
  return incidences;
}

// Twin halfedge of every halfedge (-1 on a boundary). Throws on an edge with more than two faces,
// naming the one whose first face comes first in the file.
std::vector<int> twin_halfedges(const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& triangle_polygon,
                                const std::vector<int>& file_vertex, const std::string& source) {
  const std::vector<EdgeIncidence> incidences = sorted_edge_incidences(triangles);
  std::vector<int> twin(incidences.size(), -1);
  size_t worst_begin = 0, worst_end = 0;
  for (size_t i = 0; i < incidences.size();) {
    size_t j = i + 1;
    while (j < incidences.size() && incidences[j].key == incidences[i].key) ++j;
    if (j - i == 2) {
      twin[incidences[i].halfedge] = incidences[i + 1].halfedge;
      twin[incidences[i + 1].halfedge] = incidences[i].halfedge;
    } else if (j - i > 2 && (worst_end == 0 || incidences[i].halfedge < incidences[worst_begin].halfedge)) {
      worst_begin = i;
      worst_end = j;
    }
    i = j;
  }
  if (worst_end != 0) {
    const int h = incidences[worst_begin].halfedge;
    const int a = triangles[h / 3][h % 3], b = triangles[h / 3][(h % 3 + 1) % 3];
    std::ostringstream message;
    message << source << ": non-manifold edge between vertices " << file_vertex[std::min(a, b)] << " and "
            << file_vertex[std::max(a, b)] << " (" << worst_end - worst_begin << " faces, the first is face "
            << triangle_polygon[h / 3] << ")";
    throw InputError(message.str());
  }
  return twin;
}


void check_finite_positions(const PolygonSoup& soup, const std::string& source) {
  for (size_t v = 0; v < soup.positions.size(); ++v)
    if (!soup.positions[v].allFinite()) {
      std::ostringstream message;
      message << source << ": vertex " << v << " has a non-finite coordinate (" << soup.positions[v].x() << ", "
              << soup.positions[v].y() << ", " << soup.positions[v].z() << ")";
      throw InputError(message.str());
    }
}

// Which polygons can be used at all: an index out of range is an error; fewer than three corners
// or a repeated vertex drops the polygon, with a warning.
struct UsablePolygons {
  std::vector<char> usable;
  bool has_large_polygons = false;  // some usable polygon has more than three corners
};

UsablePolygons usable_polygons(const PolygonSoup& soup, const std::string& source, std::vector<std::string>& warnings) {
  const int file_vertex_count = static_cast<int>(soup.positions.size());
  const int polygon_count = soup.polygon_count();
  UsablePolygons u;
  u.usable.assign(polygon_count, 1);
  int too_short = 0, first_too_short = -1, repeated = 0, first_repeated = -1, repeated_vertex = -1;
  for (int p = 0; p < polygon_count; ++p) {
    const std::span<const int> corners(soup.corner_vertex.data() + soup.polygon_start[p], soup.polygon_size(p));
    for (int v : corners)
      if (v < 0 || v >= file_vertex_count)
        throw InputError(source + ": face " + std::to_string(p) + " refers to vertex " + std::to_string(v) + ", but there are only " +
                         std::to_string(file_vertex_count) + " vertices (indices count from 0)");
    if (corners.size() < 3) {
      u.usable[p] = 0;
      if (too_short++ == 0) first_too_short = p;
      continue;
    }
    std::vector<int> sorted(corners.begin(), corners.end());
    std::sort(sorted.begin(), sorted.end());
    const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
    if (dup != sorted.end()) {
      u.usable[p] = 0;
      if (repeated++ == 0) first_repeated = p, repeated_vertex = *dup;
      continue;
    }
    u.has_large_polygons |= corners.size() > 3;
  }
  if (too_short > 0)
    warnings.push_back("dropped " + count_of(too_short, "face", "faces") + " with fewer than three corners (the first is face " +
                       std::to_string(first_too_short) + ")");
  if (repeated > 0)
    warnings.push_back("dropped " + count_of(repeated, "face", "faces") + " with a repeated vertex index (the first is face " +
                       std::to_string(first_repeated) + ", which uses vertex " + std::to_string(repeated_vertex) + " twice)");
  return u;
}

// The usable polygons as triangles (in file vertex indices), with their UV corners and the file face
// each came from (for messages).
struct Triangles {
  std::vector<std::array<int, 3>> vertices, uvs;
  std::vector<int> polygon;
  int triangulated_polygons = 0;
};

Triangles triangulate(const PolygonSoup& soup, const UsablePolygons& u, bool has_uvs) {
  const int polygon_count = soup.polygon_count();
  Triangles t;
  t.vertices.reserve(soup.corner_vertex.size() / 3 + 1);
  std::unordered_set<std::uint64_t> edges;
  if (u.has_large_polygons)
    for (int p = 0; p < polygon_count; ++p)
      if (u.usable[p])
        for (int i = soup.polygon_start[p]; i < soup.polygon_start[p + 1]; ++i) {
          const int next = i + 1 == soup.polygon_start[p + 1] ? soup.polygon_start[p] : i + 1;
          edges.insert(undirected_edge_key(soup.corner_vertex[i], soup.corner_vertex[next]));
        }
  for (int p = 0; p < polygon_count; ++p) {
    if (!u.usable[p]) continue;
    const int start = soup.polygon_start[p];
    const std::span<const int> corners(soup.corner_vertex.data() + start, soup.polygon_size(p));
    auto add = [&](int a, int b, int c) {
      t.vertices.push_back({corners[a], corners[b], corners[c]});
      if (has_uvs) t.uvs.push_back({soup.corner_uv[start + a], soup.corner_uv[start + b], soup.corner_uv[start + c]});
      t.polygon.push_back(p);
    };
    if (corners.size() == 3) {
      add(0, 1, 2);
      continue;
    }
    for (const auto& c : triangulate_polygon(corners, soup.positions, edges)) add(c[0], c[1], c[2]);
    ++t.triangulated_polygons;
  }
  return t;
}

// A triangle whose corners are distinct but collinear (or coincident) has no normal and no angles;
// dropping it would open a hole, so it is an error. The tolerance is relative to the longest edge,
// far below any real sliver (a 0.01 degree needle still passes).
void check_no_zero_area(const std::vector<Eigen::Vector3d>& positions, const Triangles& t, const std::string& source) {
  for (size_t i = 0; i < t.vertices.size(); ++i) {
    const Eigen::Vector3d& a = positions[t.vertices[i][0]];
    const Eigen::Vector3d& b = positions[t.vertices[i][1]];
    const Eigen::Vector3d& c = positions[t.vertices[i][2]];
    const double longest_squared = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if ((b - a).cross(c - a).norm() <= 1e-12 * longest_squared) {
      std::ostringstream message;
      message << source << ": zero-area face " << t.polygon[i] << " (its vertices " << t.vertices[i][0] << ", "
              << t.vertices[i][1] << ", " << t.vertices[i][2] << " are collinear or coincide)";
      throw InputError(message.str());
    }
  }
}

// Keeps the vertices some triangle uses (mesh.positions, mesh.file_vertex) and renumbers the triangles.
void drop_unreferenced_vertices(const PolygonSoup& soup, Triangles& t, InputMesh& mesh) {
  const int file_vertex_count = static_cast<int>(soup.positions.size());
  std::vector<int> new_index(file_vertex_count, -1);
  for (const auto& tri : t.vertices)
    for (int v : tri) new_index[v] = 0;
  for (int v = 0; v < file_vertex_count; ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int>(mesh.positions.size());
      mesh.positions.push_back(soup.positions[v]);
      mesh.file_vertex.push_back(v);
    }
  mesh.dropped_unreferenced = file_vertex_count - static_cast<int>(mesh.positions.size());
  if (mesh.dropped_unreferenced > 0)
    mesh.warnings.push_back("dropped " + count_of(mesh.dropped_unreferenced, "vertex", "vertices") + " used by no face");
  for (auto& tri : t.vertices)
    for (int& v : tri) v = new_index[v];
}

// Flips triangles so that each connected part has one orientation (its majority's); InputError for
// a non-orientable part. Returns the halfedge twins of the result.
std::vector<int> orient_consistently(Triangles& t, bool has_uvs, InputMesh& mesh, const std::string& source) {
  const int triangle_count = static_cast<int>(t.vertices.size());
  std::vector<int> twin = twin_halfedges(t.vertices, t.polygon, mesh.file_vertex, source);
  std::vector<signed char> flip(triangle_count, -1);
  std::vector<int> component;
  int flipped_total = 0;
  for (int seed = 0; seed < triangle_count; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    component.assign(1, seed);
    for (size_t next = 0; next < component.size(); ++next) {
      const int f = component[next];
      for (int k = 0; k < 3; ++k) {
        const int g = twin[3 * f + k];
        if (g < 0) continue;
        const int u = g / 3;
        // Neighbours agree when they traverse the shared edge in opposite directions.
        const bool same_direction = t.vertices[f][k] == t.vertices[u][g % 3];
        const signed char wanted = static_cast<signed char>(flip[f] ^ (same_direction ? 1 : 0));
        if (flip[u] < 0) {
          flip[u] = wanted;
          component.push_back(u);
        } else if (flip[u] != wanted) {
          throw InputError(source + ": the surface is not orientable (like a Möbius strip): the connected part containing face " +
                           std::to_string(t.polygon[seed]) + " cannot be given one consistent orientation (conflict at face " +
                           std::to_string(t.polygon[u]) + ")");
        }
      }
    }
    const int flipped = static_cast<int>(std::count_if(component.begin(), component.end(), [&](int f) { return flip[f] == 1; }));
    const bool invert = 2 * flipped > static_cast<int>(component.size());  // keep the majority's orientation
    for (int f : component) {
      if (invert) flip[f] = static_cast<signed char>(1 - flip[f]);
      if (flip[f] == 1) {
        std::swap(t.vertices[f][1], t.vertices[f][2]);
        if (has_uvs) std::swap(t.uvs[f][1], t.uvs[f][2]);
        ++flipped_total;
      }
    }
  }
  if (flipped_total == 0) return twin;
  mesh.warnings.push_back("re-oriented " + count_of(flipped_total, "face", "faces") + " to agree with their neighbours");
  return twin_halfedges(t.vertices, t.polygon, mesh.file_vertex, source);
}

// Splits non-manifold vertices into one vertex per fan. Corners 3t + k around one vertex belong to
// one fan when their triangles are connected through edges incident to that vertex. With consistent
// orientation, halfedge a->b in t and its twin b->a in u join corner a of t with corner a of u, and
// corner b of t with corner b of u.
void split_non_manifold_vertices(std::vector<std::array<int, 3>>& triangles, const std::vector<int>& twin, InputMesh& mesh) {
  const int triangle_count = static_cast<int>(triangles.size());
  UnionFind fans(3 * triangle_count);
  for (int h = 0; h < 3 * triangle_count; ++h) {
    const int g = twin[h];
    if (g < h) continue;
    const int t = h / 3, k = h % 3, u = g / 3, j = g % 3;
    fans.unite(3 * t + k, 3 * u + (j + 1) % 3);
    fans.unite(3 * t + (k + 1) % 3, 3 * u + j);
  }
  std::vector<int> fan_vertex(3 * triangle_count, -1);  // indexed by the fan's root corner
  std::vector<char> has_fan(mesh.positions.size(), 0), was_split(mesh.positions.size(), 0);
  int first_split_file_vertex = -1;
  for (int c = 0; c < 3 * triangle_count; ++c) {
    int& v = triangles[c / 3][c % 3];
    const int root = fans.find(c);
    if (fan_vertex[root] < 0) {
      if (!has_fan[v]) {
        has_fan[v] = 1;
        fan_vertex[root] = v;
      } else {
        if (!was_split[v]) {
          was_split[v] = 1;
          ++mesh.split_vertices;
          if (first_split_file_vertex < 0) first_split_file_vertex = mesh.file_vertex[v];
        }
        fan_vertex[root] = static_cast<int>(mesh.positions.size());
        const Eigen::Vector3d position = mesh.positions[v];
        mesh.positions.push_back(position);
        mesh.file_vertex.push_back(mesh.file_vertex[v]);
      }
    }
    v = fan_vertex[root];
  }
  if (mesh.split_vertices > 0)
    mesh.warnings.push_back("split " + count_of(mesh.split_vertices, "non-manifold vertex", "non-manifold vertices") +
                            " into separate fans (the first is vertex " + std::to_string(first_split_file_vertex) + ")");
}

}  // namespace

InputMesh repair_polygon_soup(const PolygonSoup& soup, const std::string& source) {
  InputMesh mesh;
  mesh.source = source;
  mesh.warnings = soup.warnings;
  check_finite_positions(soup, source);
  const UsablePolygons usable = usable_polygons(soup, source, mesh.warnings);
  const bool has_uvs = !soup.uvs.empty() && soup.corner_uv.size() == soup.corner_vertex.size();
  Triangles triangles = triangulate(soup, usable, has_uvs);
  mesh.triangulated_polygons = triangles.triangulated_polygons;
  if (triangles.vertices.empty()) throw InputError(source + ": the mesh has no faces");
  check_no_zero_area(soup.positions, triangles, source);
  drop_unreferenced_vertices(soup, triangles, mesh);
  const std::vector<int> twin = orient_consistently(triangles, has_uvs, mesh, source);
  split_non_manifold_vertices(triangles.vertices, twin, mesh);
  mesh.triangles = std::move(triangles.vertices);
  if (has_uvs) {
    mesh.uvs = soup.uvs;
    mesh.triangle_uvs = std::move(triangles.uvs);
  }
  return mesh;
}

}  // namespace physarum
