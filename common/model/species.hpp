#pragma once
// Competing species (MoMaS, paper 001 Sec. 2.5) as a simulation backend receives them: per species
// its agent count and every model parameter per intrinsic vertex (the top-level parameters with the
// species' overrides applied, maps evaluated), and the sensing matrix. Species i owns dynamic
// pheromone layer i, with its own decay and diffusion; only its agents deposit into it; what its
// sensors read is sum_j m_ij * layer_j (plus the read-stimuli).
//
// Agents are numbered species by species (species 0 holds ids 0 .. agents_0 - 1, and so on), so the
// random streams stay keyed by agent id and a one-species set is the base model bit for bit.
#include "common/model/vertex_parameters.hpp"

#include <string>
#include <vector>

namespace physarum {

struct Species {
  int agents = 0;
  VertexParameters parameters;
};

struct SpeciesSet {
  std::vector<Species> species;  // K >= 1
  std::vector<double> sensing;   // row-major K x K: sensing[i * K + j] = m_ij, what species i reads of layer j

  int count() const { return static_cast<int>(species.size()); }
  double sensing_weight(int reader, int layer) const { return sensing[static_cast<size_t>(reader * count() + layer)]; }
  int total_agents() const;
  // The species of agent `id` under the species-by-species numbering.
  int species_of_agent(int id) const;
  // The first agent id of species `s`.
  int first_agent(int s) const;
  // True for one species reading its own layer with weight 1: the base model.
  bool is_single() const { return count() == 1 && sensing.size() == 1 && sensing[0] == 1.0; }

  // One species: `agents` agents with `parameters`, reading its layer with weight 1.
  static SpeciesSet single(int agents, const VertexParameters& parameters);
};

// InputError, starting with `who`, unless there is at least one species, every species has >= 0
// agents and parameters on `vertex_count` vertices, and the matrix is K x K and finite.
void check_species(const SpeciesSet& set, int vertex_count, const std::string& who);

}  // namespace physarum
