#pragma once
// Reading a result back: the binary PLY files physarum writes (pheromone.ply, fields_full.ply,
// maps.ply) as a triangle mesh plus every per-vertex and per-face scalar property by name, so
// `physarum render` can re-colour a finished run without simulating again and a scene's maps can be
// painted in another tool and read as {"ply": FILE, ...}. It reads any PLY — ASCII (as trimesh,
// Blender's exporter option and many scripts write it), binary little- or big-endian — whose vertex
// element has scalar properties and whose face element has one list property of triangles (plus any
// scalar face properties) — the layout of our writers and of most tools' exports — and says clearly
// what it does not read.
#include "common/mesh/input_mesh.hpp"

#include <map>
#include <string>
#include <vector>

namespace physarum {

struct PlyFields {
  InputMesh mesh;  // positions from x, y, z; triangles from the face list; no UVs
  // Every vertex property other than x, y, z, in file order, as doubles (colours too: red/green/blue
  // come back as 0..255).
  std::vector<std::string> property_names;
  std::map<std::string, std::vector<double>> properties;
  // Every scalar face property (beside the vertex-index list), in file order, one value per face.
  std::vector<std::string> face_property_names;
  std::map<std::string, std::vector<double>> face_properties;

  // The vertex property `name`; InputError naming the file and the properties it has when absent.
  const std::vector<double>& property(const std::string& name) const;
  // The face property `name`; the same error when absent.
  const std::vector<double>& face_property(const std::string& name) const;
};

// Throws InputError naming `path` and the problem (missing file, an unknown format, a face that is
// not a triangle, an index out of range, a truncated body, a word of an ASCII body that is no number).
PlyFields read_ply_fields(const std::string& path);

}  // namespace physarum
