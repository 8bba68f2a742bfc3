#pragma once
// The connected pieces of a surface (vertices joined by the edges of its faces). A distance along the
// surface is infinite between two pieces, so every geodesic tool needs a seed in every piece, and the
// heat method's Poisson solve is determined only up to one constant per piece.
#include "common/surface/surface_domain.hpp"

#include <vector>

namespace physarum {

struct SurfacePieces {
  std::vector<int> piece_of_vertex;  // 0 .. count-1, numbered in the order of each piece's lowest vertex
  std::vector<int> vertex_count;     // vertices of each piece
  int count() const { return static_cast<int>(vertex_count.size()); }
};

SurfacePieces surface_pieces(const SurfaceDomain& domain);

// InputError when some piece holds none of `seeds` (distance would be infinite there); the message
// names the piece by its vertex count and one vertex, and says what `purpose` needed the seeds.
void require_seed_in_every_piece(const SurfacePieces& pieces, const std::vector<int>& seeds, const char* purpose);

}  // namespace physarum
