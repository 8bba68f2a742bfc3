#pragma once
// Pattern analysis (issue 21; the attributes paper 004 lets users ask for): a field on a surface
// segmented into spots and stripes (common/pattern/pattern_segmentation.hpp), each measured — area,
// centre, aspect ratio and orientation in its tangent frame (common/pattern/spot_shape.hpp), stripe width
// for elongated regions (common/pattern/stripe_width.hpp), the angle to a direction field when one is given
// — and the spacing of neighbouring spots (common/pattern/spot_spacing.hpp), summarized as the JSON that
// `physarum analyze` writes (analysis.json).
#include "common/base/element_data.hpp"
#include "common/pattern/face_direction_field.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/pattern/spot_shape.hpp"
#include "common/pattern/spot_spacing.hpp"

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct PatternAnalysisOptions {
  std::optional<double> threshold;               // none: default_pattern_threshold (mean - 0.5 std when below)
  // Segment {field < threshold} instead: the cells between the strands of a network, the gaps between
  // stripes (the analysis of the negated field, reported in the field's own units).
  bool below = false;
  // Regions smaller than this (in the mesh's units squared) are left out of every measure and counted
  // in dropped_regions: specks of noise that graze the threshold.
  double min_area = 0.0;
  const FaceDirectionField* direction = nullptr; // optional; must outlive the call
};

struct AnalysedRegion {
  double area = 0.0;
  SpotShape shape;
  double contour_length = 0.0;
  int holes = 0;
  bool touches_boundary = false;
  bool is_stripe = false;
  std::optional<double> stripe_width;        // stripes only
  std::optional<double> direction_angle_deg; // with a direction field, [0, 90]
};

struct PatternAnalysis {
  double threshold = 0.0;
  bool threshold_given = false;
  bool below = false;  // the regions are where the field is below the threshold
  double field_min = 0.0, field_max = 0.0;
  double surface_area = 0.0;
  double min_area = 0.0;
  int dropped_regions = 0;  // smaller than min_area
  std::vector<AnalysedRegion> regions;  // spots and stripes, in segmentation order
  std::vector<SpotPair> pairs;          // neighbouring regions (stripes included) and their distance
};

// Throws InputError (naming mesh.source) when the field does not fit the mesh, is not finite, or
// nothing is on the chosen side of the threshold (a constant field, or a threshold beyond its range).
PatternAnalysis analyze_pattern(const InputMesh& mesh, const InputVertexData<double>& field,
                                const PatternAnalysisOptions& options);

// analysis.json: {"field", "threshold", "threshold_rule", "spot_count", "stripe_count", "spots": [...],
// "spacing": {"mean", "std", "count", "pairs": [[a, b, distance], ...]}, "stripe_width": {"mean", "std",
// "count"}, "summary": {...}}. Statistics of an empty set are null.
nlohmann::json pattern_analysis_json(const PatternAnalysis& analysis, const std::string& field_name);

// Mean and (population) standard deviation; both NaN for an empty list.
struct MeanStd {
  double mean = 0.0, std = 0.0;
};
MeanStd mean_and_std(const std::vector<double>& values);

}  // namespace physarum
