#pragma once
// The controls of paper Sec. 3.3 as a scene file states them: by map NAME, before any surface
// exists (keys "read_stimuli", "write_stimuli", "spawn_weight", "bias", "spawn_heading", "boundary";
// docs/scenes.md "Controls"). Evaluated on a surface they become the arrays a
// backend reads, SimulationControls (common/setup/scene_maps.hpp does that).
#include "common/maps/map_definition.hpp"
#include "common/model/simulation_controls.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// A model parameter given by a map: {"map": NAME, "range": [lo, hi]} or a bare NAME. With a range
// the map's values 0..1 are remapped linearly to lo..hi (lo + (hi - lo) * value); without one the
// map's values are the parameter's values in the scene file's units (degrees, m/s, ...).
struct ParameterMap {
  std::string map;
  std::optional<std::array<double, 2>> range;  // {lo, hi}, file units
};

// {"map": NAME, "weight": w}: a static layer added to what sensors read (w < 0 repels).
struct ReadStimulusSpec {
  std::string map;
  double weight = 0.0;
};

// {"map": NAME, "rate": r}: r * map concentration per second added (r < 0 removes).
struct WriteStimulusSpec {
  std::string map;
  double rate = 0.0;
};

// {"direction": VECTOR_MAP, "strength": deg/s (number or scalar map name), "symmetry": 1..8}.
struct BiasSpec {
  std::string direction;
  MapOperand strength = 0.0;  // deg/s
  int symmetry = 1;
};

struct SceneControls {
  std::vector<ReadStimulusSpec> read_stimuli;
  std::vector<WriteStimulusSpec> write_stimuli;
  std::optional<MapOperand> spawn_weight;  // absent: uniform by area
  std::optional<BiasSpec> bias;
  SpawnHeading spawn_heading = SpawnHeading::Random;
  BoundaryBehaviour boundary = BoundaryBehaviour::Reflect;
};

}  // namespace physarum
