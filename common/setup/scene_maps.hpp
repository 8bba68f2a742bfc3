#pragma once
// From a scene to the arrays a simulation backend reads, once the surface exists: the scene's named
// maps evaluated on the intrinsic triangulation (common/maps/map_evaluation.hpp), then
//   the per-vertex model parameters (a parameter given by a map takes the map's values, remapped by
//     its range; every evaluated value passes the parameter table's check), and
//   the controls of Sec. 3.3 (SimulationControls: summed read- and write-stimuli, spawn weights, the
//     directional bias in rad/s, the spawn heading and the boundary behaviour).
// A scene without maps gives exactly VertexParameters::constant(scene.agent_model().parameters, n) and a
// default SimulationControls: the base model, bit for bit.
#include "common/maps/map_evaluation.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/model/simulation_controls.hpp"
#include "common/model/species.hpp"
#include "common/model/vertex_parameters.hpp"

namespace physarum {

// InputError naming the parameter's key, the map, the intrinsic vertex and the value when an
// evaluated value is outside the parameter's range (or a map cannot be evaluated on this surface).
VertexParameters vertex_parameters(const Scene& scene, const PreparedSurface& surface);

// InputError naming the key when a spawn weight is negative or all of them are zero, or a bias
// strength is negative.
SimulationControls simulation_controls(const Scene& scene, const PreparedSurface& surface);

// The scene's competing species (common/model/species.hpp): each species' parameters are `parameters`
// (the top-level ones, evaluated) with its overrides applied, numbers or maps, and the sensing matrix
// (identity when not given). A scene without "species" gives SpeciesSet::single(scene.agent_model().agents,
// parameters). InputError naming "species[i].KEY" when an override's map gives a value out of range.
SpeciesSet species_set(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps,
                       const VertexParameters& parameters);

// All three, from one evaluation of the maps (what the command line builds a backend from).
struct SceneArrays {
  VertexParameters parameters;
  SimulationControls controls;
  SpeciesSet species;
};
SceneArrays scene_arrays(const Scene& scene, const PreparedSurface& surface);
SceneArrays scene_arrays(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps);

// The same from maps already evaluated on `surface` (`physarum map` and --maps-out reuse them).
VertexParameters vertex_parameters(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps);
SimulationControls simulation_controls(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps);

// The scene with every parameter given by a map replaced by its mean over the surface (weighted by
// the vertex masses: the area average of the piecewise-linear field): one value per parameter for
// what needs one — the time-scale checks and work estimate, the steady state U of the reports and
// run.json's summary. The per-vertex values are what is simulated.
Scene with_mean_parameters(Scene scene, const VertexParameters& parameters, const SurfaceDomain& domain);

}  // namespace physarum
