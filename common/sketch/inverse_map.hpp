#pragma once
// The inverse map of a sketch (004, Sec. 5.2): from the size of the spots a user drew to the
// reaction rate that grows spots of that size, learned from training runs of the model
// (tools/sketch/make_training_data.sh writes tools/sketch/training/MODEL.csv: per run its rate, the
// median area of its whole spots and the median spacing of neighbouring spots).
//
// The map is the paper's "linear interpolation, one to one" made monotone and smooth: per rate the
// median over its seeds, the medians pooled until the attribute falls as the rate grows (pool
// adjacent violators: noise must not fold the curve), then a monotone cubic (PCHIP, Boost.Math)
// through log(rate) against log(attribute). Log-log because the equations make the pattern's length
// scale as sqrt(D / rate): a power law, which is a straight line there.
//
// That scaling also lets one training set serve any surface: multiplying every diffusion rate by
// kappa stretches the pattern by sqrt(kappa) (x = sqrt(kappa) x' turns kappa D laplacian into
// D laplacian'), so spots kappa times the trained areas are grown by the trained rates with kappa D.
// scale_for_range picks kappa when a sketch asks for spots outside the trained sizes.
#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct TrainingRun {
  double rate = 0.0;
  int seed = 0;
  int spots = 0;
  double spot_area = 0.0;  // m^2, median over the spots clear of the boundary
  double spacing = 0.0;    // m, median over neighbouring pairs
  double stripe_width = 0.0;  // m, the stripes' mean width (the stripe model's runs; 0 without the column)
};

// The CSV of make_training_data.sh ('#' lines are its provenance; then the header
// rate,seed,steps,spots,spot_area,spacing and, optional, stripes,stripe_width). Runs with neither a
// measured area (no whole spot) nor a stripe width are kept out. InputError naming `where` for a missing column or a value that is not a positive number.
std::vector<TrainingRun> read_training_runs(const std::string& csv, const std::string& where);

// One attribute of the pattern (spot area, or spacing) as a function of the rate, inverted.
class RateMap {
 public:
  // Per run: its rate and the attribute measured on it (> 0). InputError with fewer than three
  // distinct rates, or when, after pooling, fewer than three distinct attribute values remain.
  RateMap(const std::vector<double>& rate, const std::vector<double>& attribute, const std::string& attribute_name);

  // The rate whose patterns have `attribute`; nullopt outside the trained range.
  std::optional<double> rate_for(double attribute) const;
  // The trained range of the attribute (the pooled medians' extremes).
  double smallest() const { return attribute_.front(); }
  double largest() const { return attribute_.back(); }
  const std::string& attribute_name() const { return name_; }
  // The trained power law's exponent: attribute ~ rate^exponent between the range's two ends (the
  // equations give -1 for an area and -1/2 for a length; the mesh and the segmentation bend that).
  double exponent() const;

  // Leave one rate out: each pooled point's rate predicted by the map built without it (its
  // neighbours only: the two ends are left out, a map does not extrapolate), as the median of
  // |log(predicted / trained)| turned back into a relative error exp(.) - 1.
  double cross_validated_error() const;

 private:
  RateMap() = default;
  std::string name_;
  std::vector<double> attribute_;  // pooled medians, ascending
  std::vector<double> rate_;       // their rates, descending (bigger spots need a slower reaction)
};

// The factor kappa by which every diffusion rate is multiplied so that each wanted attribute value,
// divided by kappa^exponent, lies in the map's trained range (`exponent`: 1 for an area, 0.5 for a
// length): 1 when they already do, else the factor that centres the wanted range (geometrically)
// in the trained one. nullopt when the wanted range is wider than the trained one.
std::optional<double> scale_for_range(const RateMap& map, double smallest_wanted, double largest_wanted, double exponent);

}  // namespace physarum
