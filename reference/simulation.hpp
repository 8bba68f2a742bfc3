#pragma once
// The serial reference simulation of the extended slime-mold model (paper Sec. 3.2-3.3): the oracle
// every faster backend is judged against. One step, in this order:
//
//   1. sense + steer   (sensing_steering.hpp) every agent whose turn decision is due
//   2. move + deposit  (movement.hpp, deposition.hpp) along the path, into an amount buffer
//   3. turnover        (turnover.hpp) age, exposure, respawn
//   4. pheromone       (pheromone.hpp) diffusion-decay of Eq. 6 / 7, with this step's deposits
//   5. time += dt
//
// How the step's deposits enter the pheromone step (4): they are the source term s of
// du/dt = -R u + s, integrated consistently with each scheme. Forward Euler evaluates the source
// explicitly, u' = (I - dt R) u + dt s: decay/diffuse first, then add the deposits. Backward Euler
// evaluates everything at the new time, (I + dt R) u' = u + dt s: add the deposits, then solve.
// With either, the total amount obeys m' = (1 - k dt) m + D resp. (1 + k dt) m' = m + D, whose
// fixed point is exactly D / (k dt): the steady-state mean is exactly U (Eq. 5) in expectation,
// not U (1 +- k dt).
//
// All randomness comes from Philox streams keyed (seed, agent), counter (step, purpose)
// (common/random_streams.hpp), so a run is bit-reproducible. step() allocates nothing and
// recomputes no geometry: every buffer is sized once here (counted in
// tests/test_reference_allocations.cpp; with a spatially varying diffuse rate the backward-Euler
// solve goes through Eigen's SparseLU, whose solve() allocates).
#include "common/scene.hpp"
#include "common/simulation_backend.hpp"
#include "common/surface_domain.hpp"
#include "common/trace.hpp"
#include "common/vertex_parameters.hpp"
#include "reference/agents.hpp"
#include "reference/pheromone.hpp"

#include <cstdint>
#include <vector>

namespace physarum {

class ReferenceSimulation final : public SimulationBackend {
 public:
  // The domain must outlive the simulation (it is read, never copied). Throws InputError when the
  // parameter arrays do not match the domain or a setting is out of range.
  ReferenceSimulation(const SurfaceDomain& domain, VertexParameters params, const SimulationSettings& settings);
  // Convenience: constant parameters from a scene (agents, time_step, seed, integrator from it too).
  ReferenceSimulation(const SurfaceDomain& domain, const Scene& scene);

  void step() override;

  double time() const override { return time_; }
  long long steps_taken() const override { return steps_taken_; }
  double time_step() const { return settings_.time_step; }
  std::uint32_t seed() const { return settings_.seed; }

  const SurfaceDomain& domain() const { return domain_; }
  const VertexParameters& parameters() const { return params_; }
  const Agents& agents() const { return agents_; }
  Agents& agents() { return agents_; }  // tests place agents by hand
  const std::vector<double>& concentration() const { return pheromone_.concentration(); }
  ReferencePheromone& pheromone() { return pheromone_; }
  const ReferencePheromone& pheromone() const { return pheromone_; }
  SimulationCounters counters() const override { return counters_; }

  // ---- SimulationBackend ----
  std::vector<double> concentration_values() const override { return pheromone_.concentration(); }
  void fill_concentration(double value) override { pheromone_.fill(value); }
  FieldStatistics field_statistics(double U) const override;
  std::vector<int> agent_faces() const override { return agents_.face; }
  std::string backend_name() const override { return "reference"; }
  std::string device_name() const override { return "CPU (serial reference, 1 thread)"; }
  // Hazard rate 1/tau per vertex (turnover.hpp).
  const std::vector<double>& hazard_rate() const { return hazard_rate_; }

 private:
  void move_and_deposit();

  const SurfaceDomain& domain_;
  VertexParameters params_;
  SimulationSettings settings_;
  std::vector<double> hazard_rate_;
  Agents agents_;
  ReferencePheromone pheromone_;

  double time_ = 0.0;
  long long steps_taken_ = 0;
  SimulationCounters counters_;

  // Per-step scratch, sized once.
  std::vector<double> deposit_amount_;  // amount per vertex deposited during the current step
  std::vector<TraceSegment> segments_;
};

}  // namespace physarum
