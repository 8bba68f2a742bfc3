#include "tools/bench/bench_session.hpp"

#include "opencl/face_records.hpp"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/diffusion_decay.hpp"
#include "reference/diffusion_decay.hpp"
#include "api/backend_factory.hpp"
#include "common/model/vertex_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace physarum::cli {

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

StepTiming time_steps(SimulationBackend& sim, double min_seconds, long long min_steps, long long max_steps) {
  sim.run(3);
  sim.finish();
  const SimulationCounters before = sim.counters();
  const Clock::time_point start = Clock::now();
  long long steps = 0;
  while (steps < max_steps && (steps < min_steps || seconds_since(start) < min_seconds)) {
    sim.step();
    sim.finish();
    ++steps;
  }
  StepTiming t;
  t.steps = steps;
  t.seconds_per_step = seconds_since(start) / static_cast<double>(steps);
  const SimulationCounters after = sim.counters();
  const double agent_steps = static_cast<double>(after.agent_steps - before.agent_steps);
  t.crossings_per_agent_step =
      agent_steps > 0 ? static_cast<double>(after.face_crossings + after.sensor_face_crossings - before.face_crossings -
                                            before.sensor_face_crossings) /
                            agent_steps
                      : 0.0;
  return t;
}

Scene scene_scaled_to(const SurfaceDomain& d) {
  constexpr double kNativeFaces = 20000;  // where the default scene's lengths are used as they are
  const double scale = std::sqrt(kNativeFaces / d.face_count);  // h over the native resolution's h
  Scene s = bench_scene(d.face_count);
  s.agent_model().parameters[Param::sensor_distance] *= scale;
  s.agent_model().parameters[Param::move_rate] *= scale;
  s.agent_model().parameters[Param::diffuse_rate] *= scale * scale;
  return s;
}

MemoryBandwidth::MemoryBandwidth(const opencl::ComputeContext& compute) : device_(compute) {
  if (opencl::tuning_for(compute.device).host_triad) host_.emplace();
}

double MemoryBandwidth::bytes_per_second(int repeats) {
  const double device = device_.bytes_per_second(repeats);
  return host_ ? std::max(device, host_->bytes_per_second(repeats)) : device;
}

const char* MemoryBandwidth::memory() const {
  return host_ ? "host memory: the better of an OpenCL and a host triad" : "device memory: OpenCL triad";
}

BenchSession::BenchSession(const BenchOptions& o)
    : options_(o), compute_(opencl::make_compute_context(o.device)), bandwidth_(compute_) {}

std::string BenchSession::surface_spec(const std::string& name) const {
  if (name.rfind("shape:", 0) == 0) return name;
  const std::filesystem::path p = std::filesystem::path(options_.meshes) / name;
  return std::filesystem::exists(p) ? p.string() : "";
}

const SurfaceDomain* BenchSession::domain(const std::string& name, double max_circumradius) {
  const std::string spec = surface_spec(name);
  if (spec.empty()) return nullptr;
  return &surfaces_.get(bench_surface(spec, max_circumradius)).domain;
}

Workload BenchSession::workload(const std::string& name, double max_circumradius, const Scene& scene,
                                BackendChoice backend) const {
  return bench_workload(name, surface_spec(name), max_circumradius, scene, backend);
}

Row BenchSession::run(const std::string& sweep, const Workload& w) {
  const double min_seconds = options_.quick ? 0.15 : 0.6;
  const int agents = w.scene.agent_model().agents;
  const SurfaceDomain& d = surfaces_.get(w.surface).domain;
  const std::unique_ptr<SimulationBackend> sim = make_backend(w, surfaces_, &compute_);
  const StepTiming t = time_steps(*sim, min_seconds, 3, 1000);
  const std::string backend = to_string(w.backend);
  Row r{sweep, w.label, backend, agents, d.face_count, d.vertex_count, t.seconds_per_step,
        agents / t.seconds_per_step, t.crossings_per_agent_step, 0.0};
  r.crossings_per_second = r.agent_steps_per_second * r.crossings_per_agent_step;
  std::printf("%-12s %-18s %-9s %9d agents %8d faces  %9.3f ms/step  %8.3g agent-steps/s  %5.1f crossings/step  "
              "%8.3g crossings/s\n",
              sweep.c_str(), w.label.c_str(), backend.c_str(), agents, d.face_count, 1e3 * t.seconds_per_step,
              r.agent_steps_per_second, r.crossings_per_agent_step, r.crossings_per_second);
  std::fflush(stdout);
  rows_.push_back(r);
  return r;
}

PheromoneTiming BenchSession::pheromone_step(const SurfaceDomain& d, BackendChoice backend, Integrator integrator) {
  const Scene scene = bench_scene(0);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, d.vertex_count);
  PheromoneTiming t;
  auto time = [&](auto step, auto finish, bool beside_triad) {
    step();
    finish();
    // Beside a triad, one step per wait (the triad must run between them). Otherwise the steps go
    // in batches of up to 64 per wait, as `physarum run` issues them (it waits for the device only
    // for a statistics row, a frame or a checkpoint), so a small field's step is what a run pays
    // for it, not the device's round-trip latency: a batch of about 2 ms.
    int batch = 1;
    if (!beside_triad) {
      const Clock::time_point one = Clock::now();
      step();
      finish();
      batch = static_cast<int>(std::clamp(2e-3 / std::max(seconds_since(one), 1e-9), 1.0, 64.0));
    }
    // The best of several batches: on a shared machine the best is what the code can do, the rest
    // is other tenants.
    const Clock::time_point start = Clock::now();
    double best = INFINITY;
    for (int steps = 0; steps < 5 || (steps < 30 && seconds_since(start) < 0.3); ++steps) {
      if (beside_triad)
        t.triad_bytes_per_second = std::max(t.triad_bytes_per_second, bandwidth_.bytes_per_second(1));
      const Clock::time_point step_start = Clock::now();
      for (int s = 0; s < batch; ++s) step();
      finish();
      best = std::min(best, seconds_since(step_start) / batch);
    }
    return best;
  };
  if (backend == BackendChoice::OpenCL) {
    // Numbered as a simulation numbers the device's field, so it reads memory the same way.
    opencl::OpenCLDiffusionDecay field(compute_, opencl::in_device_vertex_order(d), params, integrator, scene.time_step);
    const bool forward = integrator == Integrator::Forward;
    field.fill(1.0);
    t.seconds = time([&] { field.step(); }, [&] { compute_.queue.finish(); }, forward);
    t.sub_steps = field.sub_steps();
    if (forward) t.bytes_per_step = field.forward_bytes_per_sub_step() * field.sub_steps();
    return t;
  }
  ReferenceDiffusionDecay model(d, params, integrator, scene.time_step);
  IntrinsicVertexData<double> u(static_cast<size_t>(d.vertex_count), 1.0);
  t.seconds = time([&] { model.step(u); }, [] {}, false);
  t.sub_steps = model.sub_steps();
  return t;
}

}  // namespace physarum::cli
