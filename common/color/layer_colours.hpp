#pragma once
// Colour sets per layer (paper 004, Sec. 2.3, Figs. 7 and 8): each layer of a pattern has its own
// colour set, a colour map spread over that layer's field from its valley (lowest value: the set's
// first colour) to its peak (highest value: the last colour), whatever the model's units. Two layers
// composite: inside the first layer's (frozen) spots the first layer's field through the first set,
// everywhere else the final field through the second, so the spots of each layer keep their own
// colours (a leopard's rosette: the first layer's disc in one set, the ring of second-layer spots
// around it in the other).
#include "common/color/color_map_json.hpp"
#include "common/color/color_mapping.hpp"

#include <vector>

namespace physarum {

class LayerColours {
 public:
  // One layer: its set over the field's valley and peak. `field` must not be empty.
  LayerColours(const ColorMapSettings& set, const std::vector<double>& field);
  // Two layers: the first set over the first layer's field, the second over the final field's values
  // outside the first layer's spots (`first_share` 0 there; 1 inside them), so the second layer's
  // spots reach the second set's last colour even where the first layer's stand taller. InputError
  // when the sizes differ, a field is empty, or no vertex lies outside the first layer's spots.
  LayerColours(const ColorMapSettings& first_set, const std::vector<double>& first_field, const ColorMapSettings& second_set,
               const std::vector<double>& final_field, const std::vector<double>& first_share);

  // The colour where the first layer's field is `first`, the final field `last` and the first
  // layer's share `first_share` (in [0, 1]; interpolated between vertices it blends the two sets
  // across a spot's rim). With one layer only `first` matters.
  SrgbColor at(double first, double last, double first_share) const;

 private:
  ColorMapping first_, second_;
  bool layered_ = false;
};

}  // namespace physarum
