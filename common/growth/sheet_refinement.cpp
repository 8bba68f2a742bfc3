#include "common/growth/sheet_refinement.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace physarum {
namespace {

std::uint64_t undirected_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

// A face as three vertices and the squared rest lengths of the edges opposite them.
struct RestFace {
  std::array<int, 3> v;
  std::array<double, 3> opposite;
};

// An edge that may be split: its ends and its squared rest length.
struct Split {
  int a, b;
  double length_squared;
};

// A direction given on a parent's edge vectors, on a child's: the child's corners in the parent's
// edge-vector coordinates (corner 0 at the origin, corner 1 at (1, 0), corner 2 at (0, 1)) give its
// edge vectors there, and the coefficients solve [e1' e2'] c' = c.
Eigen::Vector2d child_direction(const Eigen::Vector2d& parent, const std::array<Eigen::Vector2d, 3>& child_corners) {
  Eigen::Matrix2d edges;
  edges.col(0) = child_corners[1] - child_corners[0];
  edges.col(1) = child_corners[2] - child_corners[0];
  return edges.inverse() * parent;
}

// The per-face fields beside the faces (GrowingSheet::directions and initial_area), split with them.
struct FaceFields {
  std::vector<std::vector<Eigen::Vector2d>>& directions;
  std::vector<double>& initial_area;
};

// Splits face f of `faces` across its edge opposite corner c (the edge being split), appending the
// second child; the new vertex is `middle`.
void split_face(std::vector<RestFace>& faces, FaceFields fields, std::size_t f, int c, int middle) {
  const RestFace parent = faces[f];
  const int a = parent.v[(c + 1) % 3], b = parent.v[(c + 2) % 3], apex = parent.v[c];
  const double ab = parent.opposite[c], b_apex = parent.opposite[(c + 1) % 3], a_apex = parent.opposite[(c + 2) % 3];
  const double median = 0.5 * (a_apex + b_apex) - 0.25 * ab;  // |middle - apex|^2
  // (apex, a, middle) and (apex, middle, b): counter-clockwise like (apex, a, b).
  faces[f] = {{apex, a, middle}, {0.25 * ab, median, a_apex}};
  faces.push_back({{apex, middle, b}, {0.25 * ab, b_apex, median}});
  const std::array<Eigen::Vector2d, 3> unit{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)};
  const Eigen::Vector2d p_apex = unit[c], p_a = unit[(c + 1) % 3], p_b = unit[(c + 2) % 3], p_middle = 0.5 * (p_a + p_b);
  for (std::vector<Eigen::Vector2d>& field : fields.directions) {
    const Eigen::Vector2d d = field[f];
    field[f] = child_direction(d, {p_apex, p_a, p_middle});
    field.push_back(child_direction(d, {p_apex, p_middle, p_b}));
  }
  if (!fields.initial_area.empty()) {
    fields.initial_area[f] *= 0.5;  // the median halves the parent: equal rest areas
    fields.initial_area.push_back(fields.initial_area[f]);
  }
}

}  // namespace

int refine_sheet(GrowingSheet& sheet, double max_edge, int max_split_rounds) {
  const double bound = max_edge * max_edge;
  std::vector<RestFace> faces;
  for (std::size_t f = 0; f < sheet.topology.faces.size(); ++f)
    faces.push_back({sheet.topology.faces[f],
                     {rest_edge_length_squared(sheet.rest.face_metric[f], 0), rest_edge_length_squared(sheet.rest.face_metric[f], 1),
                      rest_edge_length_squared(sheet.rest.face_metric[f], 2)}});
  std::unordered_map<std::uint64_t, double> rest_angle;
  for (std::size_t h = 0; h < sheet.topology.hinges.size(); ++h) {
    const auto& v = sheet.topology.hinges[h].vertices;
    rest_angle[undirected_key(v[0], v[1])] = sheet.rest.hinge_angle[h];
  }
  int splits = 0;
  for (int round = 0; round < max_split_rounds; ++round) {
    // Each edge too long, once, with its length as the two faces beside it say (their mean).
    std::unordered_map<std::uint64_t, Split> chosen;
    for (const RestFace& face : faces)
      for (int c = 0; c < 3; ++c) {
        const int a = face.v[(c + 1) % 3], b = face.v[(c + 2) % 3];
        auto [it, fresh] = chosen.try_emplace(undirected_key(a, b), Split{a, b, face.opposite[c]});
        if (!fresh) it->second.length_squared = 0.5 * (it->second.length_squared + face.opposite[c]);
      }
    std::vector<Split> long_edges;
    for (const auto& [key, split] : chosen)
      if (split.length_squared > bound) long_edges.push_back(split);
    if (long_edges.empty()) break;
    // Longest first, ties by vertex: the result does not depend on the hash map's order.
    std::sort(long_edges.begin(), long_edges.end(), [](const Split& x, const Split& y) {
      return x.length_squared != y.length_squared ? x.length_squared > y.length_squared
                                                  : std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
    });
    // One split per face per round keeps every split's two faces intact.
    std::unordered_map<std::uint64_t, std::vector<std::pair<std::size_t, int>>> faces_of_edge;
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int c = 0; c < 3; ++c) faces_of_edge[undirected_key(faces[f].v[(c + 1) % 3], faces[f].v[(c + 2) % 3])].push_back({f, c});
    std::vector<char> touched(faces.size(), 0);
    for (const Split& split : long_edges) {
      const auto& beside = faces_of_edge[undirected_key(split.a, split.b)];
      if (std::any_of(beside.begin(), beside.end(), [&](const auto& fc) { return touched[fc.first] != 0; })) continue;
      const int middle = static_cast<int>(sheet.positions.size());
      sheet.positions.push_back(0.5 * (sheet.positions[split.a] + sheet.positions[split.b]));
      for (std::vector<double>& field : sheet.values) field.push_back(0.5 * (field[split.a] + field[split.b]));
      const auto angle = rest_angle.find(undirected_key(split.a, split.b));
      if (angle != rest_angle.end()) {
        rest_angle[undirected_key(split.a, middle)] = angle->second;
        rest_angle[undirected_key(middle, split.b)] = angle->second;
      }
      for (const auto& [f, c] : beside) {
        touched[f] = 1;
        split_face(faces, FaceFields{sheet.directions, sheet.initial_area}, f, c, middle);
        touched.push_back(1);
      }
      ++splits;
    }
  }
  std::vector<std::array<int, 3>> triangles;
  for (const RestFace& face : faces) triangles.push_back(face.v);
  sheet.topology = build_shell_topology(static_cast<int>(sheet.positions.size()), triangles);
  sheet.rest.face_metric.clear();
  for (const RestFace& face : faces) sheet.rest.face_metric.push_back(metric_from_edge_lengths(face.opposite));
  sheet.rest.hinge_angle.clear();
  for (const ShellHinge& hinge : sheet.topology.hinges) {
    const auto angle = rest_angle.find(undirected_key(hinge.vertices[0], hinge.vertices[1]));
    sheet.rest.hinge_angle.push_back(angle == rest_angle.end() ? 0.0 : angle->second);
  }
  return splits;
}

}  // namespace physarum
