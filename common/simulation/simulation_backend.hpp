#pragma once
// What every simulation backend offers (reference | opencl: same interface, same model, same seed). `physarum run`, the differential harness and the benchmarks
// drive a backend only through this interface, so a new backend plugs into all of them at once.
#include "common/base/element_data.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/model/diffusion_decay.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace physarum {

struct SimulationSettings {
  int agents = 0;
  double time_step = 0.0;
  std::uint32_t seed = 1;
  Integrator integrator = Integrator::Forward;
};

struct SurfaceDomain;
struct VertexParameters;
struct SimulationState;  // common/simulation/simulation_state.hpp
// The checks every backend makes on its inputs: every agent parameter map has one value per vertex,
// agents >= 0, time_step > 0 and finite, turn_frequency > 0 everywhere. Throws InputError whose
// message starts with `who` ("simulation", "opencl simulation").
void check_simulation_inputs(const SurfaceDomain& domain, const VertexParameters& params,
                             const SimulationSettings& settings, const std::string& who);

// The checks every backend makes on a layer access (the field calls of SimulationBackend below):
// the index is in [0, layer_count); values are one per vertex and all finite; a fill value is
// finite. Each throws InputError whose message starts with `who` ("simulation", "opencl
// simulation"), then `what` (the call: "set_field", "add_static_layer", ...), and names the layer.
void check_layer_index(int layer, int layer_count, const std::string& who, const std::string& what);
void check_layer_values(const IntrinsicVertexData<double>& values, int vertex_count, int layer,
                        const std::string& who, const std::string& what);
void check_layer_value(double value, int layer, const std::string& who, const std::string& what);

// The checks every backend makes in restore_state before it changes anything: one layer per layer
// of the backend with one finite value per vertex, `agent_count` agents with every attribute array
// of that length, each on a face in [0, face_count), a step count >= 0 and a finite time. Throws
// InputError whose message starts with `who` and says what does not fit.
void check_state_fits(const SimulationState& state, int layer_count, int vertex_count, int agent_count, int face_count,
                      const std::string& who);

// Running totals for throughput figures (run.json). Face crossings are the unit of work of an
// agent step: each costs one dependent read of a face record.
struct SimulationCounters {
  long long agent_steps = 0;
  long long face_crossings = 0;         // by movement traces
  long long sensor_face_crossings = 0;  // by sensor traces (three per turn decision)
  long long boundary_hits = 0;          // movement steps that reflected off a boundary
  long long respawns = 0;

  double crossings_per_agent_step() const {
    return agent_steps > 0 ? static_cast<double>(face_crossings + sensor_face_crossings) / static_cast<double>(agent_steps)
                           : 0.0;
  }
};

class SimulationBackend {
 public:
  virtual ~SimulationBackend() = default;

  virtual void step() = 0;
  // `steps` steps; a backend may enqueue them without waiting in between.
  virtual void run(long long steps) {
    for (long long i = 0; i < steps; ++i) step();
  }
  // Blocks until every enqueued step has finished (a no-op for a synchronous backend); timings
  // call it before reading the clock.
  virtual void finish() {}

  // ---- fields: the simulation's per-vertex layers ----
  // Layers 0 .. dynamic_layer_count()-1 are dynamic: step() advances them with their field model
  // (layer 0: the pheromone the agents deposit into and sense). The layers after them are static:
  // fixed maps (for the read-stimuli) that never advance and never receive deposits; they change
  // only through set_field / fill_field. Every call below takes any layer, dynamic or static; a
  // layer index out of range, a wrong number of values or a non-finite value throws InputError
  // naming the layer.
  virtual int layer_count() const = 0;  // dynamic + static
  virtual int dynamic_layer_count() const = 0;
  // Appends a static layer with `values` (one per intrinsic vertex) and returns its index (the
  // static layers follow the dynamic ones, in the order they were added).
  virtual int add_static_layer(const IntrinsicVertexData<double>& values) = 0;
  // A layer's values per intrinsic vertex (a copy; may read back from a device).
  virtual IntrinsicVertexData<double> field_values(int layer = 0) const = 0;
  virtual void set_field(const IntrinsicVertexData<double>& values, int layer = 0) = 0;
  // Sets a layer to `value` everywhere (e.g. U, so a run starts at its steady mean instead of
  // spending several decay times on the way up).
  virtual void fill_field(double value, int layer = 0) = 0;
  // Mean and coverage of a layer (on the device where there is one).
  virtual FieldStatistics field_statistics(double U, int layer = 0) const = 0;

  virtual double time() const = 0;
  virtual long long steps_taken() const = 0;
  // The intrinsic face every agent is on, in agent-id order.
  virtual std::vector<int> agent_faces() const = 0;
  virtual SimulationCounters counters() const = 0;

  // ---- checkpoints (common/simulation/simulation_state.hpp, common/run/checkpoint.hpp) ----
  // The whole evolving state, after every enqueued step has finished (a device backend reads its
  // buffers back). restore_state(save_state()) on a backend built from the same scene, surface and
  // settings continues bit for bit as the saved one would have. restore_state throws InputError when
  // the state does not fit this backend (layer count, values per layer, agent count, an agent on a
  // face that does not exist), and changes nothing then.
  virtual SimulationState save_state() const = 0;
  virtual void restore_state(const SimulationState& state) = 0;

  virtual std::string backend_name() const = 0;  // "reference", "opencl"
  virtual std::string device_name() const = 0;   // a human-readable description
};

}  // namespace physarum
