#pragma once
// From a sketch's regions to the scene that grows them (004, Secs. 5.1-5.2): each region's sketched
// spot area through the model's inverse map (common/sketch/inverse_map.hpp) to a reaction rate,
// the rates blended over the surface as a map (in logs: the rate is a scale), every diffusion rate
// multiplied by kappa when the sketched sizes lie outside the trained ones, and a run long enough
// for the slowest region's spots to form.
//
// Elongated spots: both morphogens diffuse r times slower across a direction field than along it.
// That is the isotropic system seen through a stretch (x across = sqrt(r) x'), so its spots are the
// isotropic ones squeezed across the direction: aspect (minor / major) sqrt(r), area sqrt(r) times
// the isotropic area, the major axis along the direction. The equations give this map exactly,
// where the paper learns it (LWR from aspect and axis to four grid coefficients): r = aspect^2, the
// size map asked for area / aspect, and the direction field the regions' orientations blended (as
// axes). Each region has its own ratio, blended over the surface as the rates are (a scalar map
// "sketch_ratio"; one number when the regions agree), so round and elongated spots can share a patch.
//
// Sizes, aspects and orientations are the surface's: a region's drawn ellipse goes through the
// window's map at its centre (common/sketch/sketch_domain.hpp; on a UV layout, its stretch there).
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/sketch/inverse_map.hpp"
#include "common/sketch/sketch_domain.hpp"
#include "common/sketch/sketch_regions.hpp"
#include "api/sketch/sketch_models.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum {

// The max_circumradius of the training scenes (tools/sketch/training/*.json): what a trained spot's
// size is in mesh cells.
inline constexpr double kTrainingCircumradius = 0.007;

struct SketchPlan {
  const SketchModel* model = nullptr;
  std::vector<double> wanted_area;  // m^2 per region
  std::vector<double> rate;         // per region
  double kappa = 1.0;               // every diffusion rate x kappa
  std::vector<double> ratio;        // per region, the anisotropy ratio: aspect^2 (1: isotropic)
  double trained_smallest = 0.0, trained_largest = 0.0;  // m^2, the map's range (before kappa)
  double cross_validated_error = 0.0;                    // of the rate, relative
  long long steps = 0;
  // Stripes (plan_stripes): the width asked for per region (m), the trained widths (m), and the
  // initiator cells (initiator_segments), in the input mesh's coordinates.
  std::vector<double> wanted_width;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> initiators;
  double initiator_radius = 0.0;  // input units
  // --refine multiplies a region's rate by (1 + miss)^refine_exponent: 1 for spots (areas go as
  // 1 / rate, as the trained spots do within a tenth); for stripes -1 / the trained exponent, as
  // their measured widths go as rate^-0.74, not the equations' rate^-0.5.
  double refine_exponent = 1.0;
};

// Initiator cells (004 Sec. 5.4, Fig. 16): segments kInitiatorLength stripe widths long and
// kInitiatorThickness widths thick, at random centres, enough to cover kInitiatorCover of the surface,
// each along the strokes' orientation blended at its centre and turned by a uniform draw within
// +-kInitiatorJitter degrees (the paper's "slight variations"). a is raised to kInitiatorLevel on
// them. The values are those of the experiments that chose them: 60 such segments on a 1 m^2 square
// of 2.6 cm stripes turned its labyrinth to within 3 degrees of the segments' orientation.
inline constexpr double kInitiatorLength = 6.0;
inline constexpr double kInitiatorThickness = 0.6;
inline constexpr double kInitiatorCover = 0.15;
inline constexpr double kInitiatorJitter = 5.0;
inline constexpr double kInitiatorLevel = 2.0;
// Stripes also diffuse this many times as fast across the strokes' direction as along it: the
// labyrinth squeezed across the strokes runs along them (with the initiators alone, a quadrant whose
// strokes turn 45 degrees from its neighbours' kept a coherence of 0.09; with this, 0.46). The
// isotropic stripe is then sqrt(ratio) times as wide across, so the width map is asked for
// width / sqrt(ratio), as the spot map is asked for area / aspect.
inline constexpr double kStripeAnisotropy = 0.5;

// Spots rounder than this are grown isotropic; thinner than kThinnestAspect are refused (the
// anisotropy would exceed 1 : 10, beyond what a spot a few cells wide resolves).
inline constexpr double kRoundAspect = 0.9;
inline constexpr double kThinnestAspect = 0.3;

// InputError, before anything runs, when a region asks for spots smaller than the mesh resolves
// (the smallest trained spot in cells, on a mesh of `max_circumradius`; the message says the
// smallest size), when the sketched sizes span more than the training does (it says the span and
// the nearest reachable size), or when a region's spots are thinner than kThinnestAspect.
SketchPlan plan_sketch(const SketchRegions& regions, const SketchDomain& domain, const SketchModel& model,
                       double max_circumradius);

// Stripes along strokes: each region's stripe width (stroke_regions) through the stripe model's
// inverse map to a rate, kappa when the widths lie outside the trained ones (a length: it goes as
// sqrt(kappa)), the run as long as the slowest region needs. InputError, before anything runs, for
// stripes thinner than the mesh resolves (the message says the thinnest) or widths spanning more than
// the training does (the span, and the nearest reachable width).
SketchPlan plan_stripes(const SketchRegions& regions, const SketchDomain& domain, const SketchModel& model,
                        double max_circumradius);

// Square metres per unit^2 of region k's sizes (window units^2 through the window's map at its
// centre; the mesh's units^2 for marks on the surface), and metres per unit (its square root).
double region_area_factor(const SketchRegions& regions, size_t k, const SketchDomain& domain);
double region_length_factor(const SketchRegions& regions, size_t k, const SketchDomain& domain);

// Fills plan.initiators and plan.initiator_radius (see kInitiatorLength): segments straight in the
// surface's tangent plane at window points drawn uniformly (again where a UV layout has no face),
// their count from the surface's area and the stripes' median width.
void place_initiators(SketchPlan& plan, const SketchRegions& regions, const SketchDomain& domain, std::uint32_t seed);

// A scale per region (a rate, an anisotropy ratio: > 0) at each input vertex, the regions' values
// blended at the vertex's window point in logs (on a UV seam, the blends of its window points averaged).
InputVertexData<double> scale_map(const SketchRegions& regions, const SketchDomain& domain, const InputMesh& mesh,
                                  const std::vector<double>& values);

// The direction per input face (a unit tangent vector): each region's drawn spot (a stroke's line for
// stripes) through the face's map, its major axes blended at the face's window point as axes
// (doubled angles, each region weighted by 1 - its ratio when any is squeezed).
std::vector<Eigen::Vector3d> direction_map(const SketchRegions& regions, const SketchPlan& plan, const SketchDomain& domain,
                                           const InputMesh& mesh);

// The generated scene (runnable with `physarum run`): the model, its rate from the map "sketch_rate"
// of `map_file` (relative to the scene's folder), diffusion x kappa, anisotropy along the map
// "sketch_direction" (face property "direction" of the same file) with the ratio (a number, or the
// map "sketch_ratio", property "ratio" of the file, when the regions' differ) where any ratio < 1, the
// initiator cells as the map "sketch_initiators" (a "segments" map) raising a's initial value when
// the plan has some, the plan's steps.
nlohmann::ordered_json sketch_scene_json(const SketchPlan& plan, const std::string& mesh, double area,
                                         double max_circumradius, std::uint32_t seed, const std::string& map_file);

}  // namespace physarum
