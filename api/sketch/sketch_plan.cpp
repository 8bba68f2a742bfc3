#include "api/sketch/sketch_plan.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/reaction_diffusion/reaction_models.hpp"
#include "common/sketch/median.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

namespace physarum {

double region_area_factor(const SketchRegions& regions, size_t k, const SketchDomain& domain) {
  return regions.marks ? domain.scale() * domain.scale() : domain.frame_at(regions.regions[k].center).area_factor();
}

double region_length_factor(const SketchRegions& regions, size_t k, const SketchDomain& domain) {
  return std::sqrt(region_area_factor(regions, k, domain));
}

namespace {

std::string number(double x) { return ValueRange::number(x); }

// Metres per window unit across a stroke drawn at `degrees`: the strip between two parallel window
// lines a unit apart becomes one of width (area factor) / |the line's direction on the surface|.
double width_factor(const WindowFrame& at, double degrees) {
  const Eigen::Vector2d along(std::cos(degrees * M_PI / 180.0), std::sin(degrees * M_PI / 180.0));
  return at.area_factor() / (at.stretch * along).norm();
}

// A region's spots as the surface sees them: its drawn ellipse through the window's map at its
// centre (a mark on the surface: its own shape, along its own axis).
EllipseShape surface_spot(const SketchRegions& regions, size_t k, const SketchDomain& domain) {
  const RegionAttributes& r = regions.regions[k];
  if (regions.marks) return {r.aspect, 0.0};
  return on_surface(domain.frame_at(r.center), {r.aspect, r.orientation});
}

// Each region's anisotropy ratio, its spots' aspect on the surface squared (1 for spots rounder than
// kRoundAspect); a region whose spots are thinner than kThinnestAspect is refused.
std::vector<double> region_ratios(const SketchRegions& regions, const SketchDomain& domain) {
  std::vector<double> ratios;
  for (size_t k = 0; k < regions.regions.size(); ++k) {
    const double aspect = surface_spot(regions, k, domain).aspect;
    if (aspect < kThinnestAspect)
      throw InputError("sketch: region " + std::to_string(k) + "'s spots have aspect (minor / major radius) " + number(aspect) +
                       (domain.on_uv() ? " on the surface" : "") +
                       "; the thinnest a spot can be grown is " + number(kThinnestAspect) + " (an anisotropy of 1 : " +
                       number(1.0 / (kThinnestAspect * kThinnestAspect)) + ")");
    ratios.push_back(aspect < kRoundAspect ? aspect * aspect : 1.0);
  }
  return ratios;
}

// How much each region's orientation counts where orientations are blended: by how much it is
// squeezed, 1 - its ratio (a round region's orientation means nothing), or equally when none is.
std::vector<double> axis_weights(const std::vector<double>& ratio) {
  const bool squeezed = std::any_of(ratio.begin(), ratio.end(), [](double r) { return r < 1.0; });
  std::vector<double> weights;
  for (const double r : ratio) weights.push_back(squeezed ? 1.0 - r : 1.0);
  return weights;
}

// Per-region axes (degrees) blended at a window point as axes (doubled angles: 0 and 180 degrees are
// one axis), weighted; in radians.
double blend_axes(const SketchRegions& regions, const std::vector<double>& degrees, const std::vector<double>& weights,
                  const Eigen::Vector2d& w, int chart) {
  std::vector<double> cos, sin;
  for (size_t k = 0; k < degrees.size(); ++k) {
    cos.push_back(weights[k] * std::cos(2.0 * degrees[k] * M_PI / 180.0));
    sin.push_back(weights[k] * std::sin(2.0 * degrees[k] * M_PI / 180.0));
  }
  return 0.5 * std::atan2(regions.blend(sin, w, chart), regions.blend(cos, w, chart));
}

// The model's inverse map of `attribute` (TrainingRun's spot_area or stripe_width), its range and
// cross-validated error noted in the plan.
RateMap trained_map(SketchPlan& plan, const SketchModel& model, double TrainingRun::*attribute, const std::string& name) {
  plan.model = &model;
  std::vector<double> rates, values;
  for (const TrainingRun& r : training_runs(model)) rates.push_back(r.rate), values.push_back(r.*attribute);
  RateMap map(rates, values, name);
  plan.trained_smallest = map.smallest();
  plan.trained_largest = map.largest();
  plan.cross_validated_error = map.cross_validated_error();
  return map;
}

// The regions' wanted sizes (`what`: "spot areas" in "m^2", "stripe widths" in "m") through the map:
// kappa, chosen so that every isotropic size (the size / sqrt(the region's ratio): the anisotropy
// squeezes an isotropic pattern by that) / kappa^exponent lies in the trained range (a size goes as
// kappa^exponent: 1 for an area, 1/2 for a width), each region's rate and the run's steps.
// InputError when the sizes span more than the training does.
void fit_rates(SketchPlan& plan, const RateMap& map, const std::vector<double>& wanted, double exponent,
               const std::string& what, const std::string& unit) {
  std::vector<double> isotropic;
  for (size_t k = 0; k < wanted.size(); ++k) isotropic.push_back(wanted[k] / std::sqrt(plan.ratio[k]));
  const auto [lo, hi] = std::minmax_element(wanted.begin(), wanted.end());
  const auto [iso_lo, iso_hi] = std::minmax_element(isotropic.begin(), isotropic.end());
  const std::optional<double> kappa = scale_for_range(map, *iso_lo, *iso_hi, exponent);
  if (!kappa) {
    const double span = map.largest() / map.smallest();
    throw InputError("sketch: the sketched " + what + " span " + number(*lo) + " to " + number(*hi) + " " + unit +
                     " (a factor " + number(*hi / *lo) + "); the training of " + plan.model->name + " spans a factor " +
                     number(span) + ": draw " + what + " within that factor of each other (with the largest drawn, the " +
                     "smallest reachable is " + number(*hi / span) + " " + unit + ")");
  }
  plan.kappa = *kappa;
  for (const double size : isotropic) {
    // Clamped into the range: scale_for_range centres it, rounding may leave an end a hair outside.
    const double trained = std::clamp(size / std::pow(plan.kappa, exponent), map.smallest(), map.largest());
    plan.rate.push_back(*map.rate_for(trained));
  }
  plan.steps = static_cast<long long>(std::ceil(plan.model->rate_time / *std::min_element(plan.rate.begin(), plan.rate.end())));
}

}  // namespace

SketchPlan plan_sketch(const SketchRegions& regions, const SketchDomain& domain, const SketchModel& model,
                       double max_circumradius) {
  SketchPlan plan;
  const RateMap map = trained_map(plan, model, &TrainingRun::spot_area, "spot area");
  plan.ratio = region_ratios(regions, domain);
  for (size_t k = 0; k < regions.regions.size(); ++k)
    plan.wanted_area.push_back(regions.regions[k].area * region_area_factor(regions, k, domain));
  // The smallest trained spot covers as many mesh cells as a spot of `floor` does on this mesh.
  const auto lo = std::min_element(plan.wanted_area.begin(), plan.wanted_area.end());
  const double ratio = max_circumradius / kTrainingCircumradius;
  const double floor = map.smallest() * ratio * ratio;
  if (*lo < floor) {
    const size_t region = static_cast<size_t>(lo - plan.wanted_area.begin());
    throw InputError("sketch: region " + std::to_string(region) + "'s spots (" + number(*lo) +
                     " m^2) are smaller than a mesh of max_circumradius " + number(max_circumradius) +
                     " m resolves: the smallest is " + number(floor) + " m^2 (" + number(floor / region_area_factor(regions, region, domain)) +
                     (regions.marks ? " in the mesh's units^2)" : " in window units^2)") +
                     "; draw bigger spots, give a larger --area or a smaller --max-circumradius");
  }
  // Squeezed across the direction, a spot has sqrt(ratio) times its isotropic area: the size map
  // is asked for the isotropic one.
  fit_rates(plan, map, plan.wanted_area, 1.0, "spot areas", "m^2");
  return plan;
}

SketchPlan plan_stripes(const SketchRegions& regions, const SketchDomain& domain, const SketchModel& model,
                        double max_circumradius) {
  SketchPlan plan;
  const RateMap map = trained_map(plan, model, &TrainingRun::stripe_width, "stripe width");
  plan.refine_exponent = -1.0 / map.exponent();
  plan.ratio.assign(regions.regions.size(), kStripeAnisotropy);
  for (const RegionAttributes& r : regions.regions) plan.wanted_width.push_back(r.width * width_factor(domain.frame_at(r.center), r.orientation));
  // The thinnest trained stripe spans as many mesh cells as a stripe of `floor` does on this mesh.
  const auto lo = std::min_element(plan.wanted_width.begin(), plan.wanted_width.end());
  const double floor = map.smallest() * max_circumradius / kTrainingCircumradius;
  if (*lo < floor) {
    const size_t region = static_cast<size_t>(lo - plan.wanted_width.begin());
    throw InputError("sketch: region " + std::to_string(region) + "'s stripes (" + number(*lo) +
                     " m wide) are thinner than a mesh of max_circumradius " + number(max_circumradius) +
                     " m resolves: the thinnest is " + number(floor) + " m (" + number(floor / width_factor(domain.frame_at(regions.regions[region].center), regions.regions[region].orientation)) +
                     " in window units); use a wider stroke class, a larger --area or a smaller --max-circumradius");
  }
  fit_rates(plan, map, plan.wanted_width, 0.5, "stripe widths", "m");
  return plan;
}

void place_initiators(SketchPlan& plan, const SketchRegions& regions, const SketchDomain& domain, std::uint32_t seed) {
  std::vector<double> width, orientation;
  for (const RegionAttributes& r : regions.regions) width.push_back(r.width), orientation.push_back(r.orientation);
  const std::vector<double> weights = axis_weights(plan.ratio);
  const double typical_width = median(plan.wanted_width);  // m
  const auto count = static_cast<size_t>(std::ceil(kInitiatorCover * domain.surface_area() /
                                                   (kInitiatorLength * kInitiatorThickness * typical_width * typical_width)));
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), jitter(-kInitiatorJitter, kInitiatorJitter);
  plan.initiators.clear();
  // A UV layout leaves gaps between its charts: centres drawn there are drawn again (a bounded number
  // of times: a layout that covers almost none of the window places fewer segments).
  for (size_t tries = 0; plan.initiators.size() < count && tries < 100 * count; ++tries) {
    const Eigen::Vector2d centre(unit(random) * domain.window().x(), unit(random) * domain.window().y());
    const std::optional<Eigen::Vector3d> middle = domain.surface_point(centre);
    if (!middle) continue;
    const int chart = domain.chart_at(centre);
    const double angle = blend_axes(regions, orientation, weights, centre, chart) + jitter(random) * M_PI / 180.0;
    const Eigen::Vector2d half =
        0.5 * kInitiatorLength * regions.blend(width, centre, chart) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    // The segment straight in the tangent plane at its centre, in input units.
    const Eigen::Vector3d reach = domain.frame_at(centre).to_surface(half) / domain.scale();
    plan.initiators.emplace_back(*middle - reach, *middle + reach);
  }
  plan.initiator_radius = 0.5 * kInitiatorThickness * typical_width / domain.scale();  // input units
}

InputVertexData<double> scale_map(const SketchRegions& regions, const SketchDomain& domain, const InputMesh& mesh,
                                  const std::vector<double>& values) {
  std::vector<double> logs;
  for (const double r : values) logs.push_back(std::log(r));
  InputVertexData<double> map(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    double sum = 0.0;
    if (regions.marks) {
      const std::vector<double> w = regions.marks->weights(v);
      for (size_t k = 0; k < w.size(); ++k) sum += w[k] * logs[k];
    } else {
      // A vertex on a UV seam has a window point per side: the blends averaged (in logs).
      const std::vector<Eigen::Vector2d> points = domain.vertex_window_points(v);
      const std::vector<int> charts = domain.vertex_charts(v);
      for (size_t k = 0; k < points.size(); ++k) sum += regions.blend(logs, points[k], charts[k]);
      sum /= static_cast<double>(points.size());
    }
    map[v] = std::exp(sum);
  }
  return map;
}

// The direction map of marks on the surface: at each face every mark's axis projected into the
// face's plane, blended as axes with the marks' weights at the face's corners (averaged) times their
// squeeze (axis_weights); a mark whose axis is normal to the face does not count there.
std::vector<Eigen::Vector3d> surface_direction_map(const SurfaceMarks& marks, const std::vector<double>& squeeze,
                                                   const InputMesh& mesh) {
  std::vector<Eigen::Vector3d> directions;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d e1 = (mesh.positions[static_cast<size_t>(t[1])] - a).normalized();
    const Eigen::Vector3d n = e1.cross(mesh.positions[static_cast<size_t>(t[2])] - a).normalized(), e2 = n.cross(e1);
    double c = 0.0, s = 0.0;
    for (int corner = 0; corner < 3; ++corner) {
      const std::vector<double> w = marks.weights(static_cast<size_t>(t[static_cast<size_t>(corner)]));
      for (size_t k = 0; k < marks.size(); ++k) {
        const Eigen::Vector2d axis(marks.axis[k].dot(e1), marks.axis[k].dot(e2));  // its length: how far it lies in the face
        const double angle = 2.0 * std::atan2(axis.y(), axis.x()), weight = w[k] * squeeze[k] * axis.squaredNorm();
        c += weight * std::cos(angle), s += weight * std::sin(angle);
      }
    }
    const double angle = 0.5 * std::atan2(s, c);
    directions.push_back(std::cos(angle) * e1 + std::sin(angle) * e2);
  }
  return directions;
}

std::vector<Eigen::Vector3d> direction_map(const SketchRegions& regions, const SketchPlan& plan, const SketchDomain& domain,
                                           const InputMesh& mesh) {
  const std::vector<double> weights = axis_weights(plan.ratio);
  if (regions.marks) return surface_direction_map(*regions.marks, weights, mesh);
  std::vector<double> axes(regions.regions.size());
  std::vector<Eigen::Vector3d> directions;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const WindowFrame frame = domain.frame_of_face(f);
    // Each region's drawn spot (a stroke: a line, aspect 0) as this face sees it, its major axis.
    for (size_t k = 0; k < axes.size(); ++k) {
      const RegionAttributes& r = regions.regions[k];
      axes[k] = on_surface(frame, {plan.model->stripes ? 0.0 : r.aspect, r.orientation}).orientation;
    }
    const double angle = blend_axes(regions, axes, weights, domain.face_window_point(f), domain.face_chart(f));
    directions.push_back(frame.frame * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return directions;
}

nlohmann::ordered_json sketch_scene_json(const SketchPlan& plan, const std::string& mesh, double area,
                                         double max_circumradius, std::uint32_t seed, const std::string& map_file) {
  const ReactionModel& model = *find_reaction_model(plan.model->name);
  nlohmann::ordered_json morphogens = nlohmann::ordered_json::object();
  nlohmann::ordered_json maps = {{"sketch_rate", {{"ply", map_file}, {"property", "rate"}}}};
  // One ratio for every region is a number (as a user would write it); ratios that differ a map.
  const auto [least, most] = std::minmax_element(plan.ratio.begin(), plan.ratio.end());
  const bool anisotropic = *least < 1.0;
  const nlohmann::ordered_json ratio = *least == *most ? nlohmann::ordered_json(*least) : nlohmann::ordered_json("sketch_ratio");
  if (anisotropic) maps["sketch_direction"] = {{"ply", map_file}, {"face_property", "direction"}};
  if (anisotropic && *least != *most) maps["sketch_ratio"] = {{"ply", map_file}, {"property", "ratio"}};
  for (size_t m = 0; m < model.morphogens.size(); ++m) {
    nlohmann::ordered_json entry = {{"diffusion", model.diffusion[m] * plan.kappa}};
    if (anisotropic && model.diffusion[m] > 0.0) entry["anisotropy"] = {{"direction", "sketch_direction"}, {"ratio", ratio}};
    morphogens[model.morphogens[m]] = entry;
  }
  if (!plan.initiators.empty()) {
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const auto& [a, b] : plan.initiators) points.push_back({{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}});
    maps["sketch_initiators"] = {{"segments", {{"points", points}, {"radius", plan.initiator_radius}}}};
    // a at its uniform state, raised to kInitiatorLevel on the initiator cells.
    maps["sketch_initial_a"] = {{"map", "sketch_initiators"}, {"range", {model.initial[0], kInitiatorLevel}}};
    morphogens[model.morphogens[0]]["initial"] = "sketch_initial_a";
  }
  return {{"mesh", mesh},
          {"scale_to_area", area},
          {"max_circumradius", max_circumradius},
          {"model", plan.model->name},
          {"maps", maps},
          {"parameters", {{plan.model->rate_key, "sketch_rate"}}},
          {"morphogens", morphogens},
          {"preview_morphogen", plan.model->field},
          {"time_step", 1.0},
          {"integrator", "forward"},
          {"seed", seed},
          {"steps", plan.steps}};
}

}  // namespace physarum
