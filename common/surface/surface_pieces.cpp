#include "common/surface/surface_pieces.hpp"

#include "common/base/errors.hpp"

#include <numeric>
#include <string>

namespace physarum {

SurfacePieces surface_pieces(const SurfaceDomain& domain) {
  // Union-find over the faces' corners, roots always the lowest vertex (so numbering is stable).
  std::vector<int> parent(static_cast<size_t>(domain.vertex_count));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[static_cast<size_t>(v)] != v) v = parent[static_cast<size_t>(v)] = parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
    return v;
  };
  for (const auto& f : domain.face_vertices)
    for (int k = 1; k < 3; ++k) {
      const int a = root(f[0]), b = root(f[k]);
      if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
    }
  SurfacePieces pieces;
  pieces.piece_of_vertex.assign(static_cast<size_t>(domain.vertex_count), -1);
  std::vector<int> piece_of_root(static_cast<size_t>(domain.vertex_count), -1);
  for (int v = 0; v < domain.vertex_count; ++v) {
    int& p = piece_of_root[static_cast<size_t>(root(v))];
    if (p < 0) {
      p = pieces.count();
      pieces.vertex_count.push_back(0);
    }
    pieces.piece_of_vertex[static_cast<size_t>(v)] = p;
    ++pieces.vertex_count[static_cast<size_t>(p)];
  }
  return pieces;
}

void require_seed_in_every_piece(const SurfacePieces& pieces, const std::vector<int>& seeds, const char* purpose) {
  std::vector<char> seeded(static_cast<size_t>(pieces.count()), 0);
  for (const int s : seeds) seeded[static_cast<size_t>(pieces.piece_of_vertex[static_cast<size_t>(s)])] = 1;
  for (int p = 0; p < pieces.count(); ++p) {
    if (seeded[static_cast<size_t>(p)]) continue;
    int first = 0;
    while (pieces.piece_of_vertex[static_cast<size_t>(first)] != p) ++first;
    throw InputError(std::string(purpose) + ": the surface has " + std::to_string(pieces.count()) +
                     " separate pieces and the seeds reach none of piece " + std::to_string(p + 1) + " (" +
                     std::to_string(pieces.vertex_count[static_cast<size_t>(p)]) + " vertices, intrinsic vertex " +
                     std::to_string(first) + " among them): the distance there would be infinite; give a seed on every piece");
  }
}

}  // namespace physarum
