#pragma once
// Turning a raw polygon soup (from a file or a procedural shape) into a valid InputMesh, repairing
// what can be repaired without guessing and explaining precisely what cannot.
#include "common/mesh/input_mesh.hpp"
#include "common/mesh/mesh_file_reader.hpp"

#include <string>

namespace physarum {

// Repairs, in this order:
//  - polygons with fewer than three corners or a repeated vertex index are dropped (warning);
//  - polygons with more than three corners are triangulated (counted in triangulated_polygons);
//  - vertices used by no face are dropped (counted in dropped_unreferenced);
//  - faces are re-oriented consistently per connected component, keeping the majority's
//    orientation (warning);
//  - a vertex whose triangles form several fans (an hourglass vertex, or one on several boundary
//    loops) becomes one vertex per fan (counted in split_vertices, warning).
// Throws InputError, with `source` and the first offending element in the message, for
// non-finite coordinates, out-of-range vertex indices, zero-area faces, edges with more than two
// faces, non-orientable components (Möbius strips) and meshes without faces.
InputMesh repair_polygon_soup(const PolygonSoup& soup, const std::string& source);

}  // namespace physarum
