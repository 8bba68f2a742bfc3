#pragma once
// What `physarum bench` times and how (tools/bench/command_bench.cpp runs the sweeps): one session holds
// the OpenCL device, the surfaces (built once through the shared surface loader) and the rows
// measured so far. What is timed: full steps (agents + pheromone) after three warm-up steps, until
// at least a minimum time has passed (and at least three steps); the pheromone step alone (forward
// and backward Euler). The domain's preprocessing is not timed (bench/bench_refinement covers it).
#include "common/numerics/memory_bandwidth.hpp"
#include "common/scene/scene.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/setup/workload.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/memory_bandwidth.hpp"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace physarum::cli {

struct BenchOptions {
  std::string device;
  bool quick = false;
  std::string out = "bench_out";
  std::string meshes = PHYSARUM_SHARED_MESHES;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t);

struct StepTiming {
  double seconds_per_step = 0.0;
  double crossings_per_agent_step = 0.0;
  long long steps = 0;
};

// Times steps of `sim` after a warm-up, for at least min_seconds and min_steps.
StepTiming time_steps(SimulationBackend& sim, double min_seconds, long long min_steps, long long max_steps);

// The default scene rescaled to a domain so that the work per face is the same at every resolution.
// At fixed agents and fixed distances a finer mesh is not simply more of the same work: crossings
// per agent-step grow like 1/h ~ sqrt(F) (h the edge length) and forward Euler's sub-steps like
// 1/h^2 ~ F, so the fixed-agent sweep's slope in faces measures the model (about 0.5), not whether
// the implementation scales linearly. Here agents grow with F (one per face), lengths (sensor
// distance, speed) with h, and the diffusion rate with h^2: the same pattern in units of faces, with
// the same crossings per agent-step and sub-steps per step at every resolution, so a linear
// implementation takes time proportional to F (slope 1).
Scene scene_scaled_to(const SurfaceDomain& d);

// The bandwidth of the memory the kernels read, for the roofline: a triad on the device over arrays
// far larger than its cache, and for a CPU device (whose memory is the host's) the better of that
// and a triad on the host's threads, so the bound is the best rate this memory was seen to give.
class MemoryBandwidth {
 public:
  explicit MemoryBandwidth(const opencl::ComputeContext& compute);
  double bytes_per_second(int repeats);
  const char* memory() const;

 private:
  opencl::DeviceTriad device_;
  std::optional<HostTriad> host_;
};

// One measured workload: a row of bench.csv and of bench.json's "rows".
struct Row {
  std::string sweep, surface, backend;
  int agents = 0, faces = 0, vertices = 0;
  double seconds_per_step = 0, agent_steps_per_second = 0, crossings_per_agent_step = 0, crossings_per_second = 0;
};

// The pheromone step alone: seconds per step (the best of several) and the forward-Euler sub-steps
// each step takes. OpenCL's forward Euler alternates its steps with triads, so the bandwidth it is
// compared with was measured in the same seconds, by the best of as many tries; the backward step
// is timed in batches of steps per wait for the device, as a run issues them (bench_session.cpp).
struct PheromoneTiming {
  double seconds = 0.0;
  int sub_steps = 1;
  double bytes_per_step = 0.0;          // OpenCL forward Euler: what its sub-steps read and write
  double triad_bytes_per_second = 0.0;  // OpenCL forward Euler: the triad beside it
};

class BenchSession {
 public:
  explicit BenchSession(const BenchOptions& o);

  // The mesh spec of a surface name (a file under --meshes, or shape:NAME); "" when the file is absent.
  std::string surface_spec(const std::string& name) const;
  // The surface `name` scaled to 4 m^2 and refined to max_circumradius (built once); nullptr when absent.
  const SurfaceDomain* domain(const std::string& name, double max_circumradius);

  // The workload of `scene` on the surface `name` at max_circumradius (its mesh spec resolved as
  // domain() does; the surface must exist).
  Workload workload(const std::string& name, double max_circumradius, const Scene& scene, BackendChoice backend) const;
  // Times full steps of one workload, prints its line and keeps its row.
  Row run(const std::string& sweep, const Workload& workload);
  PheromoneTiming pheromone_step(const SurfaceDomain& d, BackendChoice backend, Integrator integrator);

  MemoryBandwidth& bandwidth() { return bandwidth_; }
  const std::vector<Row>& rows() const { return rows_; }
  const opencl::ComputeContext& compute() const { return compute_; }
  SurfaceCache& surfaces() { return surfaces_; }
  const BenchOptions& options() const { return options_; }

 private:
  BenchOptions options_;
  opencl::ComputeContext compute_;
  SurfaceCache surfaces_;
  std::vector<Row> rows_;
  MemoryBandwidth bandwidth_;
};

}  // namespace physarum::cli
