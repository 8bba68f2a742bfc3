#pragma once
// The spacing of a spot pattern: the geodesic distance between the centres of neighbouring spots.
// Neighbours are the spots whose geodesic Voronoi cells touch (the surface's Delaunay graph of the
// centres): one multi-source fast-marching run (common/map_tools/fast_marching.hpp, on the analysed mesh's
// own triangles) gives every vertex its distance to the nearest centre, and its label is handed
// down from the neighbour the front reached it from (the already-accepted neighbour nearest a
// centre); an edge whose ends carry different labels joins two cells. Each pair's distance is then
// measured by fast marching from each of the two centres (starting at the centre triangle's corner
// nearest the centre) to the other centre (interpolated in its triangle), and the two are averaged:
// exact on a flat surface up to the offset of the start corner from the true centre (at most
// about half an edge), first order on curved ones. Each spot's run covers only the triangles that
// touch its own cell or its neighbours' cells: a geodesic to a neighbour that crosses their shared
// border stays inside (always so for a lattice; a pair whose cells meet only far off their segment
// gets the shortest path inside the window), and the whole costs a few surface-wide runs, not one per spot.
//
// Pieces of the surface are treated separately (a spot has no neighbour across a gap), so a piece
// without spots, which fast marching could not reach, costs nothing.
#include "common/mesh/input_mesh.hpp"
#include "common/pattern/spot_shape.hpp"

#include <vector>

namespace physarum {

struct SpotPair {
  int a = -1, b = -1;     // indices into the spots, a < b
  double distance = 0.0;  // geodesic, between their centres
};

// The neighbouring pairs, sorted by (a, b). Spots on a piece of the surface with no other spot have
// no pair.
std::vector<SpotPair> neighbouring_spot_pairs(const InputMesh& mesh, const std::vector<SpotShape>& spots);

}  // namespace physarum
