#pragma once
// Turning a MESH argument (a file path or "shape:NAME") into a repaired InputMesh.
#include "common/mesh/input_mesh.hpp"

#include <string>

namespace physarum {

// Reads OBJ, OFF, PLY or STL (through OpenMesh's readers) or builds a procedural shape, then
// triangulates polygons, drops unreferenced vertices, splits non-manifold vertices and validates.
// Throws InputError naming the file, the problem and the first offending element.
InputMesh load_mesh(const std::string& spec);

}  // namespace physarum
