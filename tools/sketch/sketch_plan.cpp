#include "tools/sketch/sketch_plan.hpp"

#include "common/base/errors.hpp"
#include "common/base/value_range.hpp"
#include "common/reaction_diffusion/reaction_models.hpp"
#include "common/sketch/median.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace physarum::cli {
namespace {

std::string number(double x) { return ValueRange::number(x); }

// Each region's anisotropy ratio, aspect^2 (1 for spots rounder than kRoundAspect); a region whose
// spots are thinner than kThinnestAspect is refused.
std::vector<double> region_ratios(const SketchRegions& regions) {
  std::vector<double> ratios;
  for (size_t k = 0; k < regions.regions.size(); ++k) {
    const double aspect = regions.regions[k].aspect;
    if (aspect < kThinnestAspect)
      throw InputError("sketch: region " + std::to_string(k) + "'s spots have aspect (minor / major radius) " + number(aspect) +
                       "; the thinnest a spot can be grown is " + number(kThinnestAspect) + " (an anisotropy of 1 : " +
                       number(1.0 / (kThinnestAspect * kThinnestAspect)) + ")");
    ratios.push_back(aspect < kRoundAspect ? aspect * aspect : 1.0);
  }
  return ratios;
}

// The regions' orientations blended at a window point as axes (doubled angles: 0 and 180 degrees are
// one axis), in radians: the direction map's and the initiators' orientation. Each region weighs by
// how much it is squeezed, 1 - its ratio (a round region's orientation means nothing), or equally
// when none is.
class AxisBlend {
 public:
  AxisBlend(const SketchRegions& regions, const std::vector<double>& ratio) : regions_(regions) {
    const bool squeezed = std::any_of(ratio.begin(), ratio.end(), [](double r) { return r < 1.0; });
    for (size_t k = 0; k < regions.regions.size(); ++k) {
      const double weight = squeezed ? 1.0 - ratio[k] : 1.0, angle = 2.0 * regions.regions[k].orientation * M_PI / 180.0;
      cos_.push_back(weight * std::cos(angle));
      sin_.push_back(weight * std::sin(angle));
    }
  }
  double at(const Eigen::Vector2d& w) const { return 0.5 * std::atan2(regions_.blend(sin_, w), regions_.blend(cos_, w)); }

 private:
  const SketchRegions& regions_;
  std::vector<double> cos_, sin_;
};

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

SketchPlan plan_sketch(const SketchRegions& regions, const SketchPatch& patch, const SketchModel& model,
                       double max_circumradius) {
  SketchPlan plan;
  const RateMap map = trained_map(plan, model, &TrainingRun::spot_area, "spot area");
  plan.ratio = region_ratios(regions);
  for (const RegionAttributes& r : regions.regions) plan.wanted_area.push_back(patch.area_in_metres(r.area));
  // The smallest trained spot covers as many mesh cells as a spot of `floor` does on this mesh.
  const auto lo = std::min_element(plan.wanted_area.begin(), plan.wanted_area.end());
  const double ratio = max_circumradius / kTrainingCircumradius;
  const double floor = map.smallest() * ratio * ratio;
  if (*lo < floor) {
    const size_t region = static_cast<size_t>(lo - plan.wanted_area.begin());
    throw InputError("sketch: region " + std::to_string(region) + "'s spots (" + number(*lo) +
                     " m^2) are smaller than a mesh of max_circumradius " + number(max_circumradius) +
                     " m resolves: the smallest is " + number(floor) + " m^2 (" + number(floor / patch.area_in_metres(1.0)) +
                     " in window units^2); draw bigger spots, give a larger --area or a smaller --max-circumradius");
  }
  // Squeezed across the direction, a spot has sqrt(ratio) times its isotropic area: the size map
  // is asked for the isotropic one.
  fit_rates(plan, map, plan.wanted_area, 1.0, "spot areas", "m^2");
  return plan;
}

SketchPlan plan_stripes(const SketchRegions& regions, const SketchPatch& patch, const SketchModel& model,
                        double max_circumradius) {
  SketchPlan plan;
  const RateMap map = trained_map(plan, model, &TrainingRun::stripe_width, "stripe width");
  plan.refine_exponent = -1.0 / map.exponent();
  plan.ratio.assign(regions.regions.size(), kStripeAnisotropy);
  for (const RegionAttributes& r : regions.regions) plan.wanted_width.push_back(patch.length_in_metres(r.width));
  // The thinnest trained stripe spans as many mesh cells as a stripe of `floor` does on this mesh.
  const auto lo = std::min_element(plan.wanted_width.begin(), plan.wanted_width.end());
  const double floor = map.smallest() * max_circumradius / kTrainingCircumradius;
  if (*lo < floor) {
    const size_t region = static_cast<size_t>(lo - plan.wanted_width.begin());
    throw InputError("sketch: region " + std::to_string(region) + "'s stripes (" + number(*lo) +
                     " m wide) are thinner than a mesh of max_circumradius " + number(max_circumradius) +
                     " m resolves: the thinnest is " + number(floor) + " m (" + number(floor / patch.length_in_metres(1.0)) +
                     " in window units); use a wider stroke class, a larger --area or a smaller --max-circumradius");
  }
  fit_rates(plan, map, plan.wanted_width, 0.5, "stripe widths", "m");
  return plan;
}

void place_initiators(SketchPlan& plan, const SketchRegions& regions, const SketchPatch& patch, const InputMesh& mesh,
                      std::uint32_t seed) {
  const AxisBlend axis(regions, plan.ratio);
  std::vector<double> width;
  for (const RegionAttributes& r : regions.regions) width.push_back(r.width);
  const Eigen::Vector2d stretch = (patch.high - patch.low).cwiseQuotient(patch.window);  // input units per window unit
  const double mean_width = median(width);
  const double window_area = patch.window.prod();
  const auto count = static_cast<size_t>(std::ceil(kInitiatorCover * window_area /
                                                   (kInitiatorLength * kInitiatorThickness * mean_width * mean_width)));
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), jitter(-kInitiatorJitter, kInitiatorJitter);
  plan.initiators.clear();
  for (size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d centre(unit(random) * patch.window.x(), unit(random) * patch.window.y());
    const double angle = axis.at(centre) + jitter(random) * M_PI / 180.0;
    const Eigen::Vector2d half = 0.5 * kInitiatorLength * regions.blend(width, centre) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    auto input_point = [&](const Eigen::Vector2d& w) { return Eigen::Vector2d(patch.low + w.cwiseProduct(stretch)); };
    const Eigen::Vector2d a = input_point(centre - half), b = input_point(centre + half), middle = input_point(centre);
    double z = 0.0, nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : mesh.positions)
      if (const double d = (p.head<2>() - middle).squaredNorm(); d < nearest) nearest = d, z = p.z();
    plan.initiators.emplace_back(Eigen::Vector3d(a.x(), a.y(), z), Eigen::Vector3d(b.x(), b.y(), z));
  }
  // Half the thickness, in input units (the window's two axes averaged, as lengths are).
  plan.initiator_radius = 0.5 * kInitiatorThickness * mean_width * std::sqrt(stretch.x() * stretch.y());
}

InputVertexData<double> scale_map(const SketchRegions& regions, const SketchPatch& patch, const InputMesh& mesh,
                                  const std::vector<double>& values) {
  std::vector<double> logs;
  for (const double r : values) logs.push_back(std::log(r));
  InputVertexData<double> map(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) map[v] = std::exp(regions.blend(logs, patch.window_point(mesh.positions[v])));
  return map;
}

std::vector<Eigen::Vector3d> direction_map(const SketchRegions& regions, const std::vector<double>& ratio,
                                           const SketchPatch& patch, const InputMesh& mesh) {
  const AxisBlend axis(regions, ratio);
  const Eigen::Vector2d stretch = (patch.high - patch.low).cwiseQuotient(patch.window);  // input units per window unit
  std::vector<Eigen::Vector3d> directions;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d centroid = (mesh.positions[static_cast<size_t>(t[0])] + mesh.positions[static_cast<size_t>(t[1])] +
                                      mesh.positions[static_cast<size_t>(t[2])]) / 3.0;
    const Eigen::Vector2d w = patch.window_point(centroid);
    const double angle = axis.at(w);
    const Eigen::Vector2d d = Eigen::Vector2d(std::cos(angle), std::sin(angle)).cwiseProduct(stretch).normalized();
    directions.emplace_back(d.x(), d.y(), 0.0);
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

}  // namespace physarum::cli
