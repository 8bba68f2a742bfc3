#pragma once
// A direction field given per face of a mesh (a vector map as `physarum map` writes it: face
// properties NAME_x, NAME_y, NAME_z in input coordinates), looked up at any point near that mesh:
// the analysed result (fields_full.ply, on the intrinsic triangulation) and the map's mesh (the
// input) are different triangulations of the same surface, so a spot's centre finds its direction
// on the map's face closest to it.
#include "common/mesh/input_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

struct FaceDirectionField {
  InputMesh mesh;
  std::vector<Eigen::Vector3d> directions;  // one per face of mesh

  // The direction of the face closest to `point` (brute force: a few hundred spots against the
  // map's faces). InputError when the field has no faces or the sizes differ.
  Eigen::Vector3d at(const Eigen::Vector3d& point) const;
};

}  // namespace physarum
