#pragma once
// Segmenting a pattern on a surface (issue 21, "Pattern analysis"): the spots or stripes of a
// per-vertex field are the connected pieces of its superlevel set {f > T}, with f linear on each
// triangle. Each triangle is clipped at the iso-line f = T (linear interpolation along its edges), so
// the pieces' areas, moments and contour lengths are those of the piecewise-linear field's own
// superlevel set: exact for a field linear on every triangle, and within O(h^2) of a smooth field's
// (an iso-line drawn through interpolated edge points deviates from the true one by O(h^2)).
//
// Connectivity: the clipped part of a triangle holds all of its above-threshold corners and is convex,
// and two triangles' clipped parts meet exactly where they share an above-threshold corner, so the
// pieces are the connected components of the mesh graph restricted to above-threshold vertices.
// The same argument makes each piece homotopy equivalent to the full subcomplex on its vertices,
// whose Euler characteristic V - E + F therefore counts its holes (1 - chi for a piece with one
// outer contour): a ring around a torus or a band with a hole is told from a spot.
//
// The default threshold is the area-weighted mean plus half the area-weighted standard deviation
// (lumped vertex areas, so it does not depend on how finely the mesh is cut): it sits above the
// background of a spot pattern (whose mean is pulled up only slightly by the spots) and below the
// plateau of the spots, without the bimodal-histogram assumption Otsu's method makes.
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

// One connected piece of {f > T}: integrals over its clipped area (input coordinates).
struct PatternRegion {
  double area = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();   // integral of x dA
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();  // integral of x x^T dA
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();     // sum of clipped area x unit face normal
  double contour_length = 0.0;   // length of the iso-line f = T bounding it (mesh boundary excluded)
  int euler_characteristic = 0;  // V - E + F of the full subcomplex on its vertices (1: a disk)
  bool touches_boundary = false; // reaches the mesh boundary (an above-threshold end of a boundary edge)
  std::vector<int> vertices;     // its above-threshold vertices
  std::vector<int> faces;        // the triangles it covers in part or whole

  Eigen::Vector3d mean_position() const { return first_moment / area; }
  int hole_count() const { return euler_characteristic <= 1 ? 1 - euler_characteristic : 0; }
};

struct PatternSegmentation {
  double threshold = 0.0;
  std::vector<int> vertex_region;  // per mesh vertex: its region, or -1 at or below the threshold
  std::vector<PatternRegion> regions;
};

// The area-weighted mean + 0.5 x the area-weighted standard deviation of `field` (one value per mesh
// vertex). InputError on a size mismatch, a non-finite value or a mesh without area.
double default_pattern_threshold(const InputMesh& mesh, const InputVertexData<double>& field);

// The regions of {field > threshold}, ordered by their lowest vertex index. InputError on a size
// mismatch or a non-finite value; no error when nothing exceeds the threshold (no regions).
PatternSegmentation segment_pattern(const InputMesh& mesh, const InputVertexData<double>& field, double threshold);

}  // namespace physarum
