#include "common/mesh/shapes.hpp"

#include "common/base/errors.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>

namespace physarum {
namespace {

constexpr double pi = std::numbers::pi;

struct TriangleBuilder {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int, 3>> triangles;

  int vertex(const Eigen::Vector3d& p) {
    positions.push_back(p);
    return static_cast<int>(positions.size()) - 1;
  }
  void triangle(int a, int b, int c) { triangles.push_back({a, b, c}); }

  // Makes every triangle CCW seen from outside, where `outward(centroid)` points out of the
  // surface. Cheaper to get right than reasoning about each construction's winding by hand.
  void orient(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& outward) {
    for (auto& t : triangles) {
      const Eigen::Vector3d &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
      if ((b - a).cross(c - a).dot(outward((a + b + c) / 3.0)) < 0) std::swap(t[1], t[2]);
    }
  }

  PolygonSoup soup() const {
    PolygonSoup s;
    s.positions = positions;
    s.corner_vertex.reserve(3 * triangles.size());
    s.polygon_start.reserve(triangles.size() + 1);
    for (const auto& t : triangles) s.add_polygon({t[0], t[1], t[2]});
    return s;
  }
};

Eigen::Vector3d from_origin(const Eigen::Vector3d& p) { return p; }

PolygonSoup square() {
  constexpr int cells = 32;
  TriangleBuilder b;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) b.vertex({double(i) / cells, double(j) / cells, 0.0});
  auto id = [](int i, int j) { return j * (cells + 1) + i; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int v00 = id(i, j), v10 = id(i + 1, j), v11 = id(i + 1, j + 1), v01 = id(i, j + 1);
      // Alternating diagonals keep the grid free of a preferred direction.
      if ((i + j) % 2 == 0) {
        b.triangle(v00, v10, v11);
        b.triangle(v00, v11, v01);
      } else {
        b.triangle(v00, v10, v01);
        b.triangle(v10, v11, v01);
      }
    }
  return b.soup();
}

// Joins two concentric rings of vertices (inner may be a single centre vertex) by walking both
// around in order of angle, always advancing the ring whose next vertex comes first.
void stitch_rings(TriangleBuilder& b, const std::vector<int>& inner, const std::vector<int>& outer) {
  const int a = static_cast<int>(inner.size()), n = static_cast<int>(outer.size());
  int i = 0, j = 0;
  while (i < a || j < n) {
    const double next_inner = double(i + 1) / a, next_outer = double(j + 1) / n;
    if (j < n && (next_outer <= next_inner || i == a)) {
      b.triangle(inner[i % a], outer[j % n], outer[(j + 1) % n]);
      ++j;
    } else {
      if (a > 1) b.triangle(inner[i % a], outer[j % n], inner[(i + 1) % a]);
      ++i;
    }
  }
}

PolygonSoup disk() { return disk_soup(16); }

PolygonSoup sphere() {
  TriangleBuilder b;
  // The icosahedron's 12 vertices are the cyclic permutations of (0, ±1, ±phi); its 20 faces are
  // the vertex triples at mutual distance 2 (its edge length).
  const double phi = (1 + std::sqrt(5.0)) / 2;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      b.vertex({0, s1, s2 * phi});
      b.vertex({s1, s2 * phi, 0});
      b.vertex({s2 * phi, 0, s1});
    }
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      for (int k = j + 1; k < 12; ++k) {
        auto edge = [&](int x, int y) { return std::abs((b.positions[x] - b.positions[y]).norm() - 2.0) < 1e-9; };
        if (edge(i, j) && edge(j, k) && edge(i, k)) b.triangle(i, j, k);
      }
  for (auto& p : b.positions) p.normalize();
  for (int level = 0; level < 4; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int x, int y) {
      const auto key = std::minmax(x, y);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const int m = b.vertex((b.positions[x] + b.positions[y]).normalized());
      midpoint.emplace(key, m);
      return m;
    };
    std::vector<std::array<int, 3>> coarse;
    coarse.swap(b.triangles);
    for (const auto& t : coarse) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      b.triangle(t[0], ab, ca);
      b.triangle(ab, t[1], bc);
      b.triangle(ca, bc, t[2]);
      b.triangle(ab, bc, ca);
    }
  }
  b.orient(from_origin);
  return b.soup();
}

PolygonSoup skinny_sphere() {
  constexpr int segments = 96, rings = 16, twist = 2;
  TriangleBuilder b;
  const int south = b.vertex({0, 0, -1});
  std::vector<std::vector<int>> ring(rings);
  for (int i = 0; i < rings; ++i) {
    const double polar = pi * (i + 1) / (rings + 1);  // from the south pole
    for (int j = 0; j < segments; ++j) {
      const double longitude = 2 * pi * (j + twist * i) / segments;
      ring[i].push_back(b.vertex({std::sin(polar) * std::cos(longitude), std::sin(polar) * std::sin(longitude), -std::cos(polar)}));
    }
  }
  const int north = b.vertex({0, 0, 1});
  for (int j = 0; j < segments; ++j) {
    const int next = (j + 1) % segments;
    b.triangle(south, ring[0][j], ring[0][next]);
    b.triangle(north, ring[rings - 1][j], ring[rings - 1][next]);
  }
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int next = (j + 1) % segments;
      // Upper vertex j sits `twist` segments east of lower vertex j, so the quad is sheared and
      // lower j -- upper j+1 is its long diagonal.
      const int l0 = ring[i][j], l1 = ring[i][next], u0 = ring[i + 1][j], u1 = ring[i + 1][next];
      b.triangle(l0, l1, u1);
      b.triangle(l0, u1, u0);
    }
  b.orient(from_origin);
  return b.soup();
}

PolygonSoup torus() {
  constexpr int around = 64, tube = 24;
  static constexpr double major = 1.0, minor = 0.4;
  TriangleBuilder b;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      const double u = 2 * pi * i / around, v = 2 * pi * j / tube;
      b.vertex({(major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v)});
    }
  auto id = [](int i, int j) { return (i % around) * tube + (j % tube); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      b.triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      b.triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  b.orient([](const Eigen::Vector3d& c) {
    const Eigen::Vector3d core = major * Eigen::Vector3d(c.x(), c.y(), 0).normalized();
    return Eigen::Vector3d(c - core);
  });
  return b.soup();
}

PolygonSoup octagonal_prism() {
  constexpr int sides = 8, columns = 2, rows = 6;
  constexpr double radius = 0.5, height = 1.5;
  constexpr int per_level = sides * columns;
  TriangleBuilder b;
  std::vector<std::vector<int>> level(rows + 1);
  for (int r = 0; r <= rows; ++r) {
    const double z = -height / 2 + height * r / rows;
    for (int s = 0; s < sides; ++s) {
      const Eigen::Vector3d corner(radius * std::cos(2 * pi * s / sides), radius * std::sin(2 * pi * s / sides), z);
      const Eigen::Vector3d next(radius * std::cos(2 * pi * (s + 1) / sides), radius * std::sin(2 * pi * (s + 1) / sides), z);
      for (int c = 0; c < columns; ++c) level[r].push_back(b.vertex(corner + (next - corner) * (double(c) / columns)));
    }
  }
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < per_level; ++k) {
      const int a = level[r][k], bb = level[r][(k + 1) % per_level], c = level[r + 1][(k + 1) % per_level], d = level[r + 1][k];
      b.triangle(a, bb, c);
      b.triangle(a, c, d);
    }
  const int bottom = b.vertex({0, 0, -height / 2}), top = b.vertex({0, 0, height / 2});
  for (int k = 0; k < per_level; ++k) {
    b.triangle(bottom, level[0][k], level[0][(k + 1) % per_level]);
    b.triangle(top, level[rows][k], level[rows][(k + 1) % per_level]);
  }
  b.orient(from_origin);
  return b.soup();
}

// A unit cube centred at the origin, `cells` x `cells` squares a side (their diagonals alternating),
// its corners and edges shared between sides, and a UV layout of 3 x 2 tiles, one per side: +x, +y,
// -x along the bottom row (their v up the cube's z, going round it), +z, -z, -y along the top. Each
// tile keeps a margin of kTileMargin of its size so that a baked texture's padding stays inside it.
PolygonSoup cube() {
  constexpr int cells = 24;
  constexpr double kTileMargin = 0.04;
  struct Side {
    Eigen::Vector3d normal, u, v;  // u x v = normal: a tile seen in UV is its side seen from outside
    int column, row;
  };
  const std::array<Side, 6> sides{{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0, 0},
                                   {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, 1, 0},
                                   {{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, 2, 0},
                                   {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 0, 1},
                                   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, 1, 1},
                                   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}, 2, 1}}};
  PolygonSoup soup;
  std::map<std::array<int, 3>, int> lattice;  // a point of the cube's (2 cells + 1)^3 half-cell lattice -> vertex
  auto vertex = [&](const Eigen::Vector3d& p) {
    const std::array<int, 3> key{static_cast<int>(std::lround(2 * cells * p.x())), static_cast<int>(std::lround(2 * cells * p.y())),
                                 static_cast<int>(std::lround(2 * cells * p.z()))};
    auto [it, inserted] = lattice.try_emplace(key, static_cast<int>(soup.positions.size()));
    if (inserted) soup.positions.push_back(p);
    return it->second;
  };
  for (const Side& side : sides) {
    std::vector<int> id, uv;
    for (int j = 0; j <= cells; ++j)
      for (int i = 0; i <= cells; ++i) {
        const double a = double(i) / cells, b = double(j) / cells;
        id.push_back(vertex(0.5 * side.normal + (a - 0.5) * side.u + (b - 0.5) * side.v));
        uv.push_back(static_cast<int>(soup.uvs.size()));
        soup.uvs.emplace_back((side.column + kTileMargin + (1.0 - 2.0 * kTileMargin) * a) / 3.0,
                              (side.row + kTileMargin + (1.0 - 2.0 * kTileMargin) * b) / 2.0);
      }
    auto corner = [&](int i, int j) { return static_cast<size_t>(j * (cells + 1) + i); };
    auto add = [&](std::array<size_t, 3> c) {
      soup.add_polygon({id[c[0]], id[c[1]], id[c[2]]});
      for (const size_t k : c) soup.corner_uv.push_back(uv[k]);
    };
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const size_t v00 = corner(i, j), v10 = corner(i + 1, j), v11 = corner(i + 1, j + 1), v01 = corner(i, j + 1);
        if ((i + j) % 2 == 0) {
          add({v00, v10, v11});
          add({v00, v11, v01});
        } else {
          add({v00, v10, v01});
          add({v10, v11, v01});
        }
      }
  }
  return soup;
}

struct ShapeEntry {
  const char* name;
  PolygonSoup (*make)();
};
constexpr std::array<ShapeEntry, 7> shapes{{{"square", square},
                                            {"disk", disk},
                                            {"sphere", sphere},
                                            {"skinny-sphere", skinny_sphere},
                                            {"torus", torus},
                                            {"octagonal-prism", octagonal_prism},
                                            {"cube", cube}}};

}  // namespace

PolygonSoup disk_soup(int rings) {
  TriangleBuilder b;
  std::vector<int> previous{b.vertex({0, 0, 0})};
  for (int k = 1; k <= rings; ++k) {
    std::vector<int> ring;
    const int count = 6 * k;
    for (int j = 0; j < count; ++j) {
      const double angle = 2 * pi * j / count, radius = double(k) / rings;
      ring.push_back(b.vertex({radius * std::cos(angle), radius * std::sin(angle), 0.0}));
    }
    stitch_rings(b, previous, ring);
    previous = std::move(ring);
  }
  b.orient([](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitZ(); });
  return b.soup();
}

std::vector<std::string> shape_names() {
  std::vector<std::string> names;
  for (const auto& s : shapes) names.emplace_back(s.name);
  return names;
}

PolygonSoup make_shape_soup(const std::string& name) {
  for (const auto& s : shapes)
    if (name == s.name) return s.make();
  // disk-N: the unit disk of N rings (1 + 3 N (N + 1) vertices).
  if (name.rfind("disk-", 0) == 0 && name.size() > 5 && name.size() <= 8 &&
      std::all_of(name.begin() + 5, name.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const int rings = std::stoi(name.substr(5));
    if (rings >= 1 && rings <= kMaxDiskRings) return disk_soup(rings);
    throw InputError("shape:" + name + ": a disk has 1 to " + std::to_string(kMaxDiskRings) + " rings");
  }
  std::string valid;
  for (const auto& s : shapes) valid += std::string(valid.empty() ? "" : ", ") + s.name;
  throw InputError("shape:" + name + ": unknown shape (valid shapes: " + valid + ", disk-N)");
}

}  // namespace physarum
