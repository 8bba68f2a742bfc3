#pragma once
// The fan of faces around each vertex of a SurfaceDomain as one angular coordinate: walking
// counter-clockwise around the vertex, each corner covers the angles [start, start + angle) after the
// corners before it. The angles of a closed fan add up to the vertex's cone angle (2 pi on a flat
// surface, less at a convex vertex, more at a saddle); a fan at a boundary vertex is open and starts
// at its clockwise-most boundary edge. A vertex where faces touch only at the point has one fan per
// cluster of faces joined across edges.
//
// This is what unfolding around a vertex needs: a direction known in one face's frame becomes a
// direction in any face of the same fan by rotating through the angles in between. On a closed fan
// the same direction can be reached going either way around the vertex, and the two unfoldings
// differ by the cone angle (`turn`), so a caller that must go one way round adds or subtracts it.
#include "common/surface_domain.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

class VertexFans {
 public:
  struct Corner {
    int fan = -1;
    double start = 0.0;  // angle of the corner's edge to corner (k+1)%3, from the fan's first edge
    double angle = 0.0;  // interior angle of the face at the corner
    // Carries a vector from the face's frame into the fan's angular coordinate (the edge to corner
    // (k+1)%3 lands at angle `start`); its inverse carries fan vectors into the face.
    Rotation2 to_fan;
  };
  struct Fan {
    double cone_angle = 0.0;  // sum of the corner angles
    bool closed = false;      // goes all the way round (an interior vertex)
    Rotation2 turn;           // rotation by cone_angle
  };

  explicit VertexFans(const SurfaceDomain& domain);

  // Corner k of face f is corner(3f + k).
  const Corner& corner(int face_corner) const { return corners_[static_cast<size_t>(face_corner)]; }
  const Fan& fan(int id) const { return fans_[static_cast<size_t>(id)]; }
  int fan_count() const { return static_cast<int>(fans_.size()); }

 private:
  std::vector<Corner> corners_;
  std::vector<Fan> fans_;
};

}  // namespace physarum
