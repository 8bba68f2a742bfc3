#pragma once
// A sketch's attributes per region (004, Sec. 5.1): the window divided into n x n regions, each
// region's attributes those of the marks whose centres lie in it (medians; orientations averaged as
// axes), blended linearly between the regions' centres so that sizes and orientations change
// smoothly over the pattern (the paper's Figs. 2, 3). A region without marks takes the attributes
// of the nearest region that has some.
#include "common/sketch/sketch_attributes.hpp"
#include "common/sketch/surface_marks.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace physarum {

struct RegionAttributes {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // window units
  int spots = 0;            // the marks measured in this region (0: filled from `filled_from`)
  int filled_from = -1;     // the region whose attributes it took, or -1
  double area = 0.0;        // window units^2, median
  double aspect = 1.0;      // minor / major, median
  double orientation = 0.0; // degrees in [0, 180), the axial mean
  double spacing = 0.0;     // window units, the median length of the Delaunay edges inside the region (0: none)
  // Regions of strokes (stroke_regions): `orientation` is the strokes', `width` the stripe width asked
  // for (window units), both weighted by the length of the stroke segments whose midpoints lie here.
  int strokes = 0;          // stroke segments measured in this region
  double width = 0.0;
};

struct SketchRegions {
  int n = 1;
  Eigen::Vector2d window = Eigen::Vector2d::Ones();
  std::vector<RegionAttributes> regions;  // row by row from the bottom-left: index = row * n + column
  // A sketch of marks on the surface (surface_regions): a region per mark, in the marks' order, its
  // attributes in input units with orientation 0 (along the mark's own axis), blended by the marks'
  // weights rather than over the window (region_of and blend are then not for use).
  std::shared_ptr<const SurfaceMarks> marks;

  // The region a window point lies in (points on the window's edge or outside it: the nearest).
  int region_of(const Eigen::Vector2d& p) const;
  // Per region, the UV chart its centre lies in (a UV sketch: common/sketch/sketch_domain.hpp;
  // -1 in a gap between charts), or empty: one piece.
  std::vector<int> chart;

  // A per-region value at a window point, bilinear between the regions' centres (constant beyond
  // the outer centres): the paper's linear interpolation between neighbouring regions. Given the
  // point's chart (>= 0) and the regions' charts, regions centred on another chart take no part (the
  // others' weights renormalised; all four apart: the plain blend), so that a chart's attributes do
  // not leak across the gap onto its neighbour in the layout.
  double blend(const std::vector<double>& per_region, const Eigen::Vector2d& p, int point_chart = -1) const;
};

// The regions of a sketch's spots. InputError when n < 1 or the sketch has no spot.
SketchRegions sketch_regions(const Sketch& sketch, const SketchAttributes& attributes, int n);

// The regions of marks on a surface: one per mark.
SketchRegions surface_regions(std::shared_ptr<const SurfaceMarks> marks);

// The regions of a sketch's strokes: per region the length-weighted axial mean orientation of the
// stroke segments whose midpoints lie in it and their width classes' stripe width
// (kStripeWidthPerClass). InputError when n < 1 or the sketch has no stroke.
SketchRegions stroke_regions(const Sketch& sketch, int n);

// The axial mean of orientations (degrees, lines not arrows: doubled angles averaged), in [0, 180).
double axial_mean_degrees(const std::vector<double>& degrees);

}  // namespace physarum
