#pragma once
// Which elements the sheet's energy sums over: its triangles (membrane) and its interior edges, each
// with the two triangles that meet there (bending hinges). The sheet must be an oriented,
// edge-manifold triangle mesh (load_mesh's repair gives one); it may have boundaries.
#include <array>
#include <vector>

namespace physarum {

struct ShellHinge {
  // (x0, x1) the shared edge, x2 opposite it in faces[0] = (x0, x1, x2) (in its cyclic order), x3
  // opposite it in faces[1] = (x1, x0, x3).
  std::array<int, 4> vertices{};
  std::array<int, 2> faces{};
  // The corner (0..2) of each face that lies opposite the edge: where to read the edge's rest length
  // from that face's rest metric (common/shell/rest_metric.hpp).
  std::array<int, 2> opposite_corner{};
};

struct ShellTopology {
  int vertex_count = 0;
  std::vector<std::array<int, 3>> faces;
  std::vector<ShellHinge> hinges;
  std::vector<char> on_boundary;  // per vertex
};

// InputError when an edge has more than two faces or two faces meet at an edge with the same
// orientation (the message names the edge's vertices).
ShellTopology build_shell_topology(int vertex_count, const std::vector<std::array<int, 3>>& faces);

}  // namespace physarum
