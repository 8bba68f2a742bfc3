#pragma once
// Evaluating a scene's named maps (common/maps/map_definition.hpp) on a prepared surface: scalar maps per
// intrinsic vertex, vector maps per intrinsic face in that face's 2D frame (surface_domain.hpp:
// corner 0 at the origin, corner 1 on +x, counter-clockwise). Maps authored on the input mesh reach
// the intrinsic vertices through their input locations (SurfaceDomain::vertex_location, a face and
// barycentrics on the input): regions, ramps and textures are evaluated at that exact point of the
// input surface, a PLY vertex property is interpolated there with the barycentrics.
//
// Vector maps. A direction d given in input coordinates reaches intrinsic face T through T's CHORD
// triangle (its corners at their input locations, in input coordinates): d is projected into the
// chord triangle's plane and expressed in the orthonormal frame whose x axis runs from corner 0 to
// corner 1 and whose y axis is the plane's normal (counter-clockwise orientation) crossed with it.
// So the 2D vector keeps the projected length |d - (d.n) n| (in input units: scale_to_area does not
// turn or stretch directions) and its angle to T's first edge. On a flat part of the surface the
// chord triangle is T itself; on a curved part it differs from T's intrinsic layout by T's sagitta.
// A per-face PLY vector (NAME_x, NAME_y, NAME_z on the input mesh's faces) is read at the input face
// nearest to T's chord-triangle centroid (the input face under it; InputFaceOverlaps lists the
// candidates) and enters T as a direction does.
//
// Map tools. "diffuse", "laplace", "slope" and "gradient" are computed on the intrinsic triangulation
// itself (its Laplacian, masses and face frames); a gradient is already in each face's frame.
// "elevation" is a property of the input's extrinsic shape, computed on the input mesh and carried
// to the intrinsic vertices as a PLY vertex map is. Written back onto the input (maps_on_input), a
// gradient is the gradient of the operand's input-vertex values over each input triangle, in input
// coordinates.
#include "common/base/element_data.hpp"
#include "common/maps/map_definition.hpp"
#include "common/surface/prepared_surface.hpp"

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace physarum {

struct EvaluatedMaps {
  std::map<std::string, IntrinsicVertexData<double>> scalar;
  std::map<std::string, IntrinsicFaceData<std::array<double, 2>>> vector;

  // The map `name` of that kind; std::logic_error when absent (scene validation checks names first).
  const IntrinsicVertexData<double>& scalar_map(const std::string& name) const;
  const IntrinsicFaceData<std::array<double, 2>>& vector_map(const std::string& name) const;
};

// Every map of `maps` on `surface`. `where` starts messages (the scene file). InputError naming
// "key 'maps': map 'NAME'" when a source cannot be used on this surface: a PLY whose vertex (or
// face) count is not the input mesh's, a property it does not have, an image that cannot be read,
// a texture on a mesh without UVs, an axis along which the input is flat, a value that is not
// finite.
// `known` holds maps already evaluated (read from the map cache): they are taken as they are, and
// only the others are computed, reading them where they depend on them.
EvaluatedMaps evaluate_maps(const MapSet& maps, const PreparedSurface& surface, const std::string& where,
                            EvaluatedMaps known = {});

// The maps on the INPUT mesh, as `physarum map` and `run --maps-out` write them: scalar maps per
// input vertex (the intrinsic vertex sitting on it: the map evaluated at that vertex), vector maps
// per input face in input coordinates (a direction or PLY vector projected into the face's plane).
struct InputMaps {
  std::vector<std::pair<std::string, InputVertexData<double>>> scalar;  // in dependency order
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> vector;  // one per input triangle
};
InputMaps maps_on_input(const MapSet& maps, const PreparedSurface& surface, const EvaluatedMaps& evaluated,
                        const std::string& where);

}  // namespace physarum
