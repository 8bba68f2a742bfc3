#include "common/output/maps_ply.hpp"

#include "common/base/errors.hpp"
#include "common/output/ply_writer.hpp"

#include <vector>

namespace physarum {

void write_maps_ply(const std::string& path, const InputMesh& input, const InputMaps& maps) {
  if (maps.scalar.empty() && maps.vector.empty()) throw InputError(path + ": the scene defines no maps (key 'maps') to write");
  std::vector<PlyField> vertex_fields;
  for (const auto& [name, values] : maps.scalar) vertex_fields.push_back(PlyField{name, values});
  // The components as separate arrays, which must outlive the write.
  std::vector<std::vector<double>> components;
  components.reserve(3 * maps.vector.size());
  std::vector<PlyFaceField> face_fields;
  for (const auto& [name, vectors] : maps.vector)
    for (int c = 0; c < 3; ++c) {
      std::vector<double> column(vectors.size());
      for (size_t f = 0; f < vectors.size(); ++f) column[f] = vectors[f][c];
      components.push_back(std::move(column));
      face_fields.push_back(PlyFaceField{name + "_" + static_cast<char>('x' + c), components.back()});
    }
  FieldColoring coloring;  // the first scalar map over its own range: a quick look, the values are the properties
  write_fields_ply(path, input, vertex_fields, face_fields, coloring,
                   "named maps of a scene: scalar maps per input vertex, vector maps per face (NAME_x, NAME_y, NAME_z)");
}

}  // namespace physarum
