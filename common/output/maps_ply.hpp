#pragma once
// A scene's named maps as a PLY file (`physarum map`, `physarum run --maps-out`).
#include "common/maps/map_evaluation.hpp"

#include <string>

namespace physarum {

// Writes `maps` as properties of the input mesh (common/output/ply_writer.hpp): each scalar map a float
// vertex property of its name, each vector map the float face properties NAME_x, NAME_y, NAME_z;
// atomic. InputError when there is no map to write.
void write_maps_ply(const std::string& path, const InputMesh& input, const InputMaps& maps);

}  // namespace physarum
