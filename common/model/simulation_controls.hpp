#pragma once
// The controls of paper Sec. 3.3 as a simulation backend receives them: every map already evaluated
// on the intrinsic triangulation (common/ evaluates the scene's named maps; the backends only read
// arrays). Parameter maps are not here: they are the per-vertex parameters (vertex_parameters.hpp).
//
// Every member has a neutral default, and a default-constructed SimulationControls is the base
// model exactly: a backend given it must run bit for bit as it did before controls existed.
#include "common/base/element_data.hpp"

#include <array>
#include <optional>
#include <string>

namespace physarum {

// What happens to an agent whose move reaches a boundary edge of an open surface.
enum class BoundaryBehaviour {
  Reflect,    // mirrored at the edge and walks on (the base model)
  Terminate,  // turned over at once and respawned (the ginkgo margin of Fig. 18)
};

// The heading a (re)spawned agent starts with.
enum class SpawnHeading {
  Random,  // uniform on the circle (the base model)
  Bias,    // along the local bias direction (Fig. 8); random where the direction has zero length
};

// Directional bias (Fig. 6): each step the agent rotates toward the closest of the `symmetry`
// rotated copies of the local direction, at a rate proportional to the angle to it times the
// strength: d(delta)/dt = -strength * delta for the signed angle delta (radians) from that copy to
// the heading, integrated exactly over the step (the heading turns by delta * (1 - exp(-strength *
// dt)) toward the copy, so it never overshoots).
struct DirectionalBias {
  // Per intrinsic face, in that face's own 2D frame (surface_domain.hpp). Only the direction counts
  // (the strength says how much); a zero vector means no bias on that face.
  IntrinsicFaceData<std::array<double, 2>> direction;
  // Per intrinsic vertex, in rad/s (the scene gives deg/s); interpolated at the agent's position.
  IntrinsicVertexData<double> strength;
  int symmetry = 1;  // n = 1..8: the copies are the direction rotated by k * 2pi/n
};

struct SimulationControls {
  // Read-stimuli, summed: sum_k w_k * map_k per intrinsic vertex, in concentration units. What a
  // sensor reads is the pheromone plus this (interpolated like the pheromone). Empty: none.
  IntrinsicVertexData<double> read_stimulus;
  // Write-stimuli, summed: sum_k r_k * map_k per intrinsic vertex, concentration per second added to
  // the pheromone independently of the agents (negative removes; the concentration never goes below
  // zero). Empty: none.
  IntrinsicVertexData<double> write_rate;
  // Spawn weights per intrinsic vertex (>= 0, not all zero): the (re)spawn density is proportional
  // to the weight interpolated linearly across each face, so a face whose three corners are zero
  // never receives an agent. Empty: uniform by area (the base model).
  IntrinsicVertexData<double> spawn_weight;
  std::optional<DirectionalBias> bias;
  SpawnHeading spawn_heading = SpawnHeading::Random;
  BoundaryBehaviour boundary = BoundaryBehaviour::Reflect;
};

struct SurfaceDomain;

// InputError, starting with `who` and naming the control and the vertex or face, unless every
// per-vertex array is empty or has one finite value per vertex (spawn weights also >= 0) and the
// bias matches the domain (common/model/directional_bias.hpp). Whether the spawn weights leave anywhere
// to spawn is common/model/spawn_distribution.hpp's check (it needs the sinks).
void check_controls(const SurfaceDomain& domain, const SimulationControls& controls, const std::string& who);

}  // namespace physarum
