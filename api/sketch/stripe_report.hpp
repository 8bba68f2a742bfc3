#pragma once
// The sketch checks its stripes (beyond 004, which leaves the gap open): per region of the strokes
// (common/sketch/sketch_regions.hpp, stroke_regions), the grown stripes' orientation and width set
// beside the sketched ones, with a verdict: report.json's stripe entries (../shared/DESIGN.md,
// "Sketches").
//
// Orientation: the structure tensor of the field's gradient, J = sum over the region's faces of
// area x g g^T (g in the window's frame): its leading eigenvector is across the stripes, so the
// stripes run along the other one. Its coherence (l1 - l2) / (l1 + l2) says how well one orientation
// describes them (0: a labyrinth with no preferred direction, 1: parallel stripes). This reads the
// whole field, not a segmentation, so stripes that cross regions are counted where they lie.
// Width: the median of the segmented stripes' widths (common/pattern/stripe_width.hpp) whose centres
// lie in the region: the measure the stripe model's training recorded.
#include "common/mesh/input_mesh.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/sketch/sketch_regions.hpp"
#include "common/sketch/sketch_domain.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace physarum {

// The width within this relative error, the orientation within this many degrees (the issue's
// round trip asks 15).
inline constexpr double kWidthTolerance = 0.25;
inline constexpr double kStripeOrientationTolerance = 15.0;

struct StripeMeasure {
  int stripes = 0;           // segmented stripes whose centres lie in the region
  double width = 0.0;        // m, median (0: no stripe)
  double orientation = 0.0;  // degrees in [0, 180), the window's frame
  double coherence = 0.0;    // [0, 1]
};

// Per region (SketchRegions order), from the run's field on the input surface (fields_full.ply: the
// mesh in input coordinates and the field per vertex) and its analysis.
std::vector<StripeMeasure> measure_stripes(const InputMesh& mesh, const std::vector<double>& field,
                                           const PatternAnalysis& analysis, const SketchRegions& regions,
                                           const SketchDomain& domain);

// The region's relative miss of its sketched width (generated / sketched - 1); infinity without stripes.
double width_miss(const StripeMeasure& generated, double sketched_width);

// One region's report entry: {"center", "sketched_strokes", "sketched": {"orientation", "width"},
// "generated": {"stripes", "orientation", "coherence", "width"}, "verdict": {"orientation", "width"}},
// lengths in the input mesh's units; the arguments in metres.
nlohmann::ordered_json stripe_region_report(const RegionAttributes& sketched, double sketched_width_m,
                                            const StripeMeasure& generated, const SketchDomain& domain);

}  // namespace physarum
