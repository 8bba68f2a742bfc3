#pragma once
// The controls of paper Sec. 3.3 as a scene file states them: by map NAME, before any surface
// exists (keys "read_stimuli", "write_stimuli", "spawn_weight", "bias", "spawn_heading", "boundary";
// docs/scenes.md "Controls"). Evaluated on a surface they become the arrays a
// backend reads, SimulationControls (common/setup/scene_maps.hpp does that).
#include "common/maps/map_definition.hpp"
#include "common/model/simulation_controls.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

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

// Reads the controls' keys of a scene object (absent keys: no control). InputError naming the key
// for a malformed entry; the maps named are checked by validate_controls.
SceneControls read_controls(const nlohmann::json& scene, const std::string& source);

// Every map a control names exists in `maps` with the kind it needs; weights, rates and strengths
// are finite and in range; "spawn_heading": "bias" has a bias.
void validate_controls(const SceneControls& controls, const MapSet& maps, const std::string& source);

}  // namespace physarum
