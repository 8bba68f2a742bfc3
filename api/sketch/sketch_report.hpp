#pragma once
// The sketch checks its own result (beyond 004, which leaves the gap open): the grown pattern is
// segmented and measured (common/pattern/pattern_analysis.hpp), its whole spots (clear of the
// surface's boundary) assigned to the sketch's regions by their centres, and per region the
// generated median area, aspect, orientation and spacing set beside the sketched ones with a verdict
// per attribute: report.json (../shared/DESIGN.md, "Sketches").
#include "common/pattern/pattern_analysis.hpp"
#include "common/sketch/sketch_regions.hpp"
#include "common/sketch/sketch_domain.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace physarum {

// What a region's spots must match: the area and the spacing within this relative error (the
// issue's round trip asks 25 % of the median area).
inline constexpr double kAreaTolerance = 0.25;
inline constexpr double kSpacingTolerance = 0.25;
// ... the aspect within this absolute difference, and the orientation within this many degrees where
// the sketched spots are elongated (aspect <= kOrientedAspect; rounder ones have no orientation to judge).
inline constexpr double kAspectTolerance = 0.15;
inline constexpr double kOrientationTolerance = 15.0;
inline constexpr double kOrientedAspect = 0.6;

struct RegionMeasure {
  int spots = 0;             // whole spots whose centres lie in the region
  double area = 0.0;         // m^2, median
  // The spots' shapes as drawn in the window (each pulled back through the window's map at its
  // centre, common/sketch/sketch_domain.hpp), to set beside the sketched ones; for marks on the
  // surface, the orientation is the angle (0 to 90 degrees) from the mark's axis:
  double aspect = 1.0;       // minor / major, median
  double orientation = 0.0;  // degrees in [0, 180) in the window's frame, axial mean
  double spacing = 0.0;      // m, median over neighbouring pairs with both centres in the region (0: none)
};

// Per region (SketchRegions order), from an analysis of the run's field on the input surface
// (fields_full.ply: input coordinates).
// `first_layer`: per vertex, frozen spots of a first layer (a cascade's second layer), whose regions
// (those centred on a frozen vertex) are left out; empty for none.
std::vector<RegionMeasure> measure_regions(const PatternAnalysis& analysis, const SketchRegions& regions,
                                           const SketchDomain& domain, const std::vector<char>& first_layer = {});

// The region's relative miss of its sketched area (generated / sketched - 1); infinity without spots.
double area_miss(const RegionMeasure& generated, double sketched_area);

// One region's report entry: {"center", "sketched": {...}, "generated": {...}, "verdict": {...}},
// lengths (`scale`: metres per input unit) and the centre (as given) in the input mesh's units (as `physarum analyze` reports them; metres when
// the mesh is not rescaled); the arguments in metres. `shaped`: the plan grew elongated spots (an anisotropy); without it the
// aspect and orientation are reported and judged "not controlled" (round spots asked for).
nlohmann::ordered_json region_report(const RegionAttributes& sketched, double sketched_area_m2, double sketched_spacing_m,
                                     const RegionMeasure& generated, const nlohmann::ordered_json& center, double scale,
                                     bool shaped);

// A region's centre as report.json gives it: the input surface's point at the window point, x and y
// on a patch, x, y and z on a UV layout (null where the layout has no face there).
nlohmann::ordered_json center_json(const SketchDomain& domain, const Eigen::Vector2d& window_point);

// The difference of two axes' angles in degrees, in [0, 90].
double axis_difference(double a, double b);

}  // namespace physarum
