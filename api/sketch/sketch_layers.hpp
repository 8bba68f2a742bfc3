#pragma once
// A second layer of spots (004 Secs. 2.1.4 and 2.3, Figs. 5 and 12; Turk's cascade): `physarum sketch
// --layer2 SKETCH2` grows the first sketch's spots, freezes them, and grows the second sketch's
// (smaller) spots between them. The second run starts from the first's fields, every morphogen held
// (a Dirichlet region) where the first layer's spot field is above its segmentation threshold: at the
// first layer's values, so the new spots grow around standing spots, or with --rosettes at the
// model's uniform state, so that the frozen spots vanish and the new ones ring the empty discs
// (Turk's leopard rosettes).
//
// The check, on the final field segmented as `physarum analyze` does: a region that contains frozen
// vertices is a first-layer spot (with the skirt its standing values spread around it); every other
// region is a second-layer spot. A second-layer spot overlaps a frozen one when its peak (a strict
// local maximum of the field at a free vertex) lies inside a first-layer spot's region: a frozen
// spot's skirt falls away from it and has no peak of its own. The distance along the surface (fast
// marching) from each new spot's centre to the frozen set is set against the same distance of every
// free vertex (what spots placed without regard to the first layer would have): rosettes gather
// round the frozen discs, more of their spots near one (within 3/4 of the free surface's median
// distance) than of the free surface.
#include "common/mesh/input_mesh.hpp"
#include "common/reaction_diffusion/reaction_models.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum {

struct Cascade {
  std::string first_fields;  // the first layer's fields_full.ply, as the second scene names it
  double threshold = 0.0;    // the first layer's segmentation threshold: its spots lie above it
  bool rosettes = false;
};

// Turns the second layer's generated scene into the cascade's: every morphogen starts from the first
// layer's field (maps "first_M"), the map "frozen" (the first layer's `field` above the threshold) is
// a Dirichlet region, held at the first layer's values or, with rosettes, at the model's uniform state.
void make_cascade_scene(nlohmann::ordered_json& scene, const ReactionModel& model, const std::string& field,
                        const Cascade& cascade);

struct CascadeMeasure {
  int frozen_spots = 0;  // connected sets of frozen vertices
  int spots = 0;         // second-layer spots: regions without a frozen vertex
  int overlapping = 0;   // second-layer peaks inside a first-layer spot's region
  std::vector<double> spot_distance;  // per second-layer spot: centre to the frozen set along the surface (m)
  std::vector<double> free_distance;  // that distance of every free vertex (m)
};

// The frozen vertices: the first layer's field at or above its threshold.
std::vector<char> frozen_vertices(const std::vector<double>& first_field, double threshold);

// Measures the second layer on the final surface (`mesh`: fields_full.ply's, input coordinates;
// `scale`: metres per input unit) from its field and segmentation threshold.
CascadeMeasure measure_cascade(const InputMesh& mesh, const std::vector<double>& field, double threshold,
                               const std::vector<char>& frozen, double scale);

// report.json's "layer2" summary: counts, the overlapping peaks, the distances' medians, a histogram,
// the near shares and the verdict (cascade: no overlap; rosettes: more spots near than surface).
nlohmann::ordered_json cascade_json(const CascadeMeasure& m, bool rosettes);

}  // namespace physarum
