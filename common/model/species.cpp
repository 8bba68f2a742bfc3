#include "common/model/species.hpp"

#include "common/base/errors.hpp"

#include <cmath>

namespace physarum {

int SpeciesSet::total_agents() const {
  int total = 0;
  for (const Species& s : species) total += s.agents;
  return total;
}

int SpeciesSet::species_of_agent(int id) const {
  for (int s = 0; s < count(); ++s) {
    if (id < species[static_cast<size_t>(s)].agents) return s;
    id -= species[static_cast<size_t>(s)].agents;
  }
  return count() - 1;  // past the end: the caller's id is out of range; the last species is the safe answer
}

int SpeciesSet::first_agent(int s) const {
  int first = 0;
  for (int i = 0; i < s; ++i) first += species[static_cast<size_t>(i)].agents;
  return first;
}

SpeciesSet SpeciesSet::single(int agents, const VertexParameters& parameters) {
  SpeciesSet set;
  set.species.push_back(Species{agents, parameters});
  set.sensing = {1.0};
  return set;
}

void check_species(const SpeciesSet& set, int vertex_count, const std::string& who) {
  if (set.species.empty()) throw InputError(who + ": no species (a simulation needs at least one)");
  const size_t k = set.species.size();
  for (size_t s = 0; s < k; ++s) {
    if (set.species[s].agents < 0)
      throw InputError(who + ": species " + std::to_string(s) + " has " + std::to_string(set.species[s].agents) +
                       " agents (must be >= 0)");
    if (set.species[s].parameters.vertex_count() != vertex_count)
      throw InputError(who + ": species " + std::to_string(s) + " has parameters on " +
                       std::to_string(set.species[s].parameters.vertex_count()) + " vertices, the surface has " +
                       std::to_string(vertex_count));
  }
  if (set.sensing.size() != k * k)
    throw InputError(who + ": the sensing matrix has " + std::to_string(set.sensing.size()) + " entries; " +
                     std::to_string(k) + " species need " + std::to_string(k * k));
  for (size_t e = 0; e < set.sensing.size(); ++e)
    if (!std::isfinite(set.sensing[e]))
      throw InputError(who + ": sensing[" + std::to_string(e / k) + "][" + std::to_string(e % k) + "] is not finite");
}

}  // namespace physarum
