#pragma once
// What an agent backend is built from, read off a scene: the backends (reference/, opencl/) take the
// surface domain, per-vertex parameters and SimulationSettings and never see a Scene; these are the
// few scene-to-model readings that more than one front end needs.
#include "common/model/vertex_parameters.hpp"
#include "common/scene/scene.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"

namespace physarum {

// agents, time_step, seed and the pheromone integrator of the scene.
SimulationSettings simulation_settings(const Scene& scene);

// Every parameter at the scene's constant value on every vertex of `domain` (a scene whose
// parameters are maps goes through common/setup/scene_maps.hpp instead).
VertexParameters constant_parameters(const Scene& scene, const SurfaceDomain& domain);

// Eq. 5's U for the scene's agent count and (constant) parameters on a surface of `area`.
double uniform_steady_state(const Scene& scene, double area);

// The steady mean the time-discrete model reaches, over U (common/model/discrete_steady_state.hpp),
// for a scene whose mean is U in the continuous model (steady_mean_is_U) with `parameters` on
// `domain`: the forward-Euler sub-steps are those both backends take (forward_euler_stable_step with
// these diffuse and decay rates).
double expected_mean_over_U(const Scene& scene, const VertexParameters& parameters, const SurfaceDomain& domain);

}  // namespace physarum
