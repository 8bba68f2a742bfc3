#pragma once
// Keeping a growing sheet's resolution: every edge whose rest length exceeds a bound is split at its
// midpoint, and the two faces beside it in two (longest edges first, repeated until none is too
// long), so the mesh stays conforming. What the split carries over:
// - rest metrics: each child face's rest edge lengths are its parent's (halves of the split edge; the
//   new edge across the parent has the parent triangle's median length), so the children tile their
//   parent's rest shape exactly and the rest area does not change;
// - rest dihedral angles: the halves of a split edge keep the edge's, the new edges inside a parent
//   face are flat in the rest state (0);
// - positions: the split edge's current midpoint (the next equilibrium solve relaxes it);
// - per-vertex values (morphogen concentrations): the mean of the edge's two ends, as the paper
//   does: linear interpolation along the edge, exact for a field linear there;
// - per-face directions (coefficients on the face's rest edge vectors): the same direction in the
//   parent's rest shape, written on each child's edge vectors (exact: the children's edges are
//   combinations of the parent's with coefficients 0, +-1/2, +-1);
// - per-face initial areas: split in proportion to the children's rest areas (equal halves), so a
//   face's rest area over its initial area stays the area growth of the tissue it is made of.
#include "common/shell/rest_metric.hpp"
#include "common/shell/shell_topology.hpp"

#include <Eigen/Core>

#include <vector>

namespace physarum {

struct GrowingSheet {
  ShellTopology topology;
  std::vector<Eigen::Vector3d> positions;
  ShellRestState rest;
  std::vector<std::vector<double>> values;  // per-vertex fields (each of topology.vertex_count entries)
  // Per-face direction fields, each as coefficients on the faces' rest edge vectors (face_directions).
  std::vector<std::vector<Eigen::Vector2d>> directions;
  // Per face: the rest area of the initial sheet's tissue it is made of (empty: not tracked).
  std::vector<double> initial_area;
};

// Splits until every edge's rest length is at most `max_edge`; returns the number of splits.
// `max_split_rounds` bounds the work: each round halves the longest edges.
int refine_sheet(GrowingSheet& sheet, double max_edge, int max_split_rounds = 64);

}  // namespace physarum
