/* Competing species on the device (paper 001 Sec. 2.5; mirrors reference/agent_simulation.cpp, the host
 * side is opencl/agent_simulation.cpp): compiled only when the host defines PHYSARUM_SPECIES (K > 1), so
 * the single-species kernels are the base model's text.
 *
 * Agents are numbered species by species (common/model/species.hpp), so an agent's species follows from
 * its id (the device reorders agents by face, ids travel with them): PHYSARUM_SPECIES_FIRST_IDS
 * lists the K + 1 boundaries, first id of each species and the total. Per species the device keeps
 *   - its parameter records: vertex_parameters[s * PHYSARUM_SPECIES_VERTICES + v],
 *   - its deposit cells: deposits[s * PHYSARUM_SPECIES_CELLS + v] (PHYSARUM_SPECIES_CELLS >= the
 *     vertex count, padded so each species' cells can be a sub-buffer of their own),
 *   - what its sensors read, sum_j m_sj layer_j: sensed[s * PHYSARUM_SPECIES_VERTICES + v], built
 *     by add_layer_to_sensed before the step's sensing (the read-stimulus is added where a sensor
 *     reads, sensing_steering.cl, as for one species). */
#ifndef PHYSARUM_SPECIES_CL
#define PHYSARUM_SPECIES_CL
#include "device_types.h"

#ifdef PHYSARUM_SPECIES
#if !defined(PHYSARUM_SPECIES_FIRST_IDS) || !defined(PHYSARUM_SPECIES_VERTICES) || !defined(PHYSARUM_SPECIES_CELLS)
#error "PHYSARUM_SPECIES needs PHYSARUM_SPECIES_FIRST_IDS, PHYSARUM_SPECIES_VERTICES and PHYSARUM_SPECIES_CELLS"
#endif

__constant uint physarum_species_first_id[PHYSARUM_SPECIES + 1] = {PHYSARUM_SPECIES_FIRST_IDS};

/* The species of agent `id`: the last species whose first id is <= id. */
int species_of(const uint id) {
  int s = 0;
  for (int i = 1; i < PHYSARUM_SPECIES; ++i)
    if (id >= physarum_species_first_id[i]) s = i;
  return s;
}

/* Agent `id`'s own parameter records, sensed field and deposit cells. */
__global const PhysarumAgentParameters* species_parameters(__global const PhysarumAgentParameters* vertex_parameters,
                                                           const uint id) {
  return vertex_parameters + species_of(id) * PHYSARUM_SPECIES_VERTICES;
}
__global const float* species_sensed(__global const float* sensed, const uint id) {
  return sensed + species_of(id) * PHYSARUM_SPECIES_VERTICES;
}
int species_cells(const uint id) { return species_of(id) * PHYSARUM_SPECIES_CELLS; }

/* Adds layer j's contribution to every species' sensed field: sensed_s += m_sj layer_j, where
 * sensing is the row-major K x K matrix (row s = what species s reads). `first` (j == 0) starts the
 * sums instead of adding to them. */
__kernel void add_layer_to_sensed(__global float* sensed, __global const float* layer,
                                  __global const float* sensing, const int j, const int first) {
  const int v = get_global_id(0);
  if (v >= PHYSARUM_SPECIES_VERTICES) return;
  const float value = layer[v];
  for (int s = 0; s < PHYSARUM_SPECIES; ++s) {
#ifdef PHYSARUM_FAULT_SPECIES_MATRIX_TRANSPOSED
    const float m = sensing[j * PHYSARUM_SPECIES + s]; /* planted fault: species s reads with column s */
#else
    const float m = sensing[s * PHYSARUM_SPECIES + j];
#endif
    __global float* out = &sensed[s * PHYSARUM_SPECIES_VERTICES + v];
    *out = first ? m * value : *out + m * value;
  }
}
#endif /* PHYSARUM_SPECIES */

/* The movement walks carry, per lane, the offset of its agent's deposit cells (species_cells) from
 * the agent step down to deposition.cl: an extra parameter only with PHYSARUM_SPECIES, so the
 * single-species functions keep their signatures. */
#ifdef PHYSARUM_SPECIES
#define PHYSARUM_SPECIES_CELL_OFFSETS_PARAMETER , const lane_int* cell_offsets
#define PHYSARUM_SPECIES_CELL_OFFSETS(x) , x
#define PHYSARUM_SPECIES_CELL_OFFSET_PARAMETER , const lane_int cell_offset
#define PHYSARUM_SPECIES_CELL_OFFSET(x) , x
#else
#define PHYSARUM_SPECIES_CELL_OFFSETS_PARAMETER
#define PHYSARUM_SPECIES_CELL_OFFSETS(x)
#define PHYSARUM_SPECIES_CELL_OFFSET_PARAMETER
#define PHYSARUM_SPECIES_CELL_OFFSET(x)
#endif

#endif /* PHYSARUM_SPECIES_CL */
