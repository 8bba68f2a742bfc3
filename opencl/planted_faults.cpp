#include "opencl/planted_faults.hpp"

#include "common/base/errors.hpp"

namespace physarum::opencl {

const std::vector<PlantedFault>& planted_faults() {
  static const std::vector<PlantedFault> faults = {
      {"sensor-angle", "PHYSARUM_FAULT_SENSOR_ANGLE", "sensor angle 15 % too wide"},
      {"deposit-endpoint", "PHYSARUM_FAULT_DEPOSIT_ENDPOINT", "deposit at the end of the step, not along the path"},
      {"no-decay-substep", "PHYSARUM_FAULT_NO_DECAY_SUBSTEP", "the first forward-Euler sub-step skips decay"},
      {"no-reflect", "PHYSARUM_FAULT_NO_REFLECT", "agents stop at boundaries instead of reflecting"},
      {"uniform-face", "PHYSARUM_FAULT_UNIFORM_FACE", "respawn face not weighted by area"},
      {"turn-every-step", "PHYSARUM_FAULT_TURN_EVERY_STEP", "turn decisions ignore the decision frequency"},
      {"bias-farthest-copy", "PHYSARUM_FAULT_BIAS_FARTHEST_COPY", "the bias turns toward the farthest copy of its direction"},
      {"map-at-centroid", "PHYSARUM_FAULT_MAP_AT_CENTROID",
       "agent parameters read at the face centroid instead of interpolated"},
      {"stimulus-sign", "PHYSARUM_FAULT_STIMULUS_SIGN", "the read-stimulus weight negated"},
      {"spawn-weights-ignored", "PHYSARUM_FAULT_SPAWN_WEIGHTS_IGNORED", "(re)spawn uniform by area, spawn weights ignored"},
      {"species-matrix-transposed", "PHYSARUM_FAULT_SPECIES_MATRIX_TRANSPOSED",
       "species i senses with column i of the sensing matrix instead of row i"},
      // Reaction-diffusion (opencl/reaction_diffusion.hpp).
      {"rd-swap-diffusion", "PHYSARUM_FAULT_RD_SWAP_DIFFUSION",
       "reaction-diffusion: the first two morphogens diffuse with each other's stiffness (D_u and D_v exchanged)"},
      {"rd-no-feed", "PHYSARUM_FAULT_RD_NO_FEED",
       "reaction-diffusion: the feed term F (1 - u) dropped (coefficient F read as 0 in the first formula)"},
      {"rd-lane-mixup", "PHYSARUM_FAULT_RD_LANE_MIXUP",
       "reaction-diffusion with five or more morphogens: the last one diffuses by the one before it's sum (a lane "
       "mix-up of the wide vector)"},
  };
  return faults;
}

std::string fault_build_option(const std::string& name) {
  if (name.empty()) return "";
  std::string known;
  for (const PlantedFault& f : planted_faults()) {
    if (name == f.name) return std::string("-D") + f.define;
    known += std::string(known.empty() ? "" : ", ") + f.name;
  }
  throw UsageError("--fault " + name + ": unknown fault (known: " + known + ")");
}

}  // namespace physarum::opencl
