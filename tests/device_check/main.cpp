// A self-contained check of the OpenCL backend on whatever device the machine has (a GPU where one
// is lent): the surfaces are built in code (no mesh files), so the program needs nothing but an
// OpenCL driver. For each device: one agent step from identical states against the reference
// (fraction of agents that agree), the U metric over a short run, one forward-Euler pheromone step
// against the reference, canaries, the throughput of the full step at 1e5..1e7 agents on refined
// spheres, and the forward step's bytes per second against the device memory's (a triad); then
// where the backward-Euler step should solve (host factorization or device CG, by size: what
// DeviceTuning::host_implicit_solve_max_vertices is set from) and the reaction-diffusion explicit
// step against the triad.
//   physarum_device_check [--device SPEC] [--only SECTION[,SECTION...]]
// SECTION: checks, throughput, implicit, rd (all when --only is not given).
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/setup/workload.hpp"
#include "opencl/face_records.hpp"
#include "opencl/host_cholesky_solve.hpp"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/runtime/memory_bandwidth.hpp"
#include "opencl/diffusion_decay.hpp"
#include "opencl/reaction_diffusion.hpp"
#include "opencl/agent_simulation.hpp"
#include "model_scene.hpp"
#include "one_step_comparison.hpp"
#include "probe_checks.hpp"
#include "reference/diffusion_decay.hpp"
#include "reference/agent_simulation.hpp"
#include "rough_gray_scott.hpp"
#include "api/backend_factory.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace physarum::opencl {
namespace {

using testing::check;

Scene scene(int agents, Integrator integrator) { return testing::model_scene(agents, 0.01, 0.5, integrator); }

// The device check's workloads: a built-in shape (scaled to `area` m^2 when given, refined to
// `max_circumradius`) with `agents` agents of the model scene, on the OpenCL backend.
Workload workload(const std::string& shape, double max_circumradius, std::optional<double> area, int agents,
                  Integrator integrator) {
  SurfaceSpec spec;
  spec.mesh = "shape:" + shape;
  spec.scale_to_area = area;
  spec.max_circumradius = max_circumradius;
  return Workload{spec.mesh, spec, scene(agents, integrator), BackendChoice::OpenCL};
}

void one_step(const ComputeContext& compute, const SurfaceDomain& domain, const std::string& label, Integrator integrator) {
  const testing::StepComparison c = testing::compare_one_step(compute, domain, scene(20000, integrator), 60);
  check(c.mismatched <= c.agents / 1000, label + ": one step from identical states, " + std::to_string(c.mismatched) +
                                             " of " + std::to_string(c.agents) + " agents disagree");
  check(!c.canaries_damaged, label + ": canaries intact");
}

void u_metric(const ComputeContext& compute, const SurfaceDomain& domain, const std::string& label, Integrator integrator) {
  const Scene sc = scene(5000, integrator);
  OpenCLAgentSimulation sim(compute, domain, constant_parameters(sc, domain), simulation_settings(sc));
  const double U = uniform_steady_state(sc, domain.total_area);
  sim.fill_field(U);
  double sum = 0.0;
  int n = 0;
  for (int s = 1; s <= 600; ++s) {
    sim.step();
    if (s > 100) sum += sim.field_statistics(U).mean / U, ++n;
  }
  check(std::abs(sum / n - 1.0) < 0.01, label + ": time-averaged mean / U = " + std::to_string(sum / n));
}

// Three forward-Euler sub-steps from a varied field against the reference (relative 1e-5, as in
// tests/test_opencl_diffusion_decay.cpp), then the step's memory throughput; vertices numbered as a
// simulation numbers them on the device.
void pheromone_forward(const ComputeContext& compute, const SurfaceDomain& surface, const std::string& label,
                       double triad_bytes_per_second) {
  const SurfaceDomain domain = in_device_vertex_order(surface);
  const int n = domain.vertex_count;
  ParameterValues rates;
  rates[Param::diffuse_rate] = 0.01;
  rates[Param::decay_rate] = 0.5;
  const VertexParameters params = VertexParameters::constant(rates, n);
  ReferenceDiffusionDecay reference(domain, params, Integrator::Forward, 1.0);
  const double dt = 2.5 * reference.stable_time_step();
  ReferenceDiffusionDecay expected(domain, params, Integrator::Forward, dt);
  OpenCLDiffusionDecay device(compute, domain, params, Integrator::Forward, dt);
  // The domain is already in the device's vertex order, so one list of values serves both.
  std::vector<double> u0(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) u0[static_cast<size_t>(i)] = 0.1 + 0.9 * ((i * 37) % 101) / 100.0;
  IntrinsicVertexData<double> want(u0);
  device.set_concentration(DeviceVertexData<double>(u0));
  expected.step(want);
  device.step();
  const DeviceVertexData<double> got = device.concentration();
  double diff = 0.0, scale = 0.0;
  for (int i = 0; i < n; ++i) {
    diff = std::max(diff, std::abs(got[static_cast<size_t>(i)] - want[static_cast<size_t>(i)]));
    scale = std::max(scale, std::abs(want[static_cast<size_t>(i)]));
  }
  const int long_rows = to_hybrid(domain.laplacian, n).overflow_rows();
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, " (%d sub-steps, %d rows past the ELL width): max difference %.3g of %.3g",
                device.sub_steps(), long_rows, diff, scale);
  check(diff <= 1e-5 * scale, label + ": forward Euler" + numbers);
  check(device.damaged_canaries().empty(), label + ": forward Euler canaries intact");
  const int steps = 50;
  device.step();
  compute.queue.finish();
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) device.step();
  compute.queue.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
  const double rate = device.forward_bytes_per_sub_step() * device.sub_steps() / seconds;
  std::printf("pheromone forward step: %d vertices, %d sub-steps (%.3g MB each), %.3f ms/step, %.3g GB/s, %.2f of the "
              "triad\n",
              n, device.sub_steps(), device.forward_bytes_per_sub_step() / 1e6, 1e3 * seconds, rate / 1e9,
              rate / triad_bytes_per_second);
}

// One throughput line; agents_per_work_item 0 is the device's automatic choice.
void throughput_line(const ComputeContext& compute, SurfaceCache& surfaces, const Workload& w,
                     int agents_per_work_item) {
  OpenCLBackendOptions options;
  options.agents_per_work_item = agents_per_work_item;
  const std::unique_ptr<SimulationBackend> sim = make_backend(w, surfaces, &compute, options);
  sim->run(5);
  sim->finish();
  const SimulationCounters before = sim->counters();
  const auto t0 = std::chrono::steady_clock::now();
  const int steps = 20;
  sim->run(steps);
  sim->finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const SimulationCounters after = sim->counters();
  const double crossings = static_cast<double>(after.face_crossings + after.sensor_face_crossings -
                                               before.face_crossings - before.sensor_face_crossings);
  const int agents = w.scene.agent_model().agents;
  std::printf("throughput: %d faces, %d agents, %s agents per work-item: %.3f ms/step, %.3g agent-steps/s, %.1f "
              "crossings/agent-step, %.3g crossings/s\n",
              surfaces.get(w.surface).domain.face_count, agents,
              agents_per_work_item == 0 ? "automatic" : std::to_string(agents_per_work_item).c_str(),
              1e3 * seconds / steps, agents * steps / seconds, crossings / (static_cast<double>(agents) * steps),
              crossings / seconds);
}

// Agent scaling with the automatic grouping, then 1e6 agents with each explicit grouping, on the
// sphere of 4 m^2 refined to `max_circumradius`.
void throughput(const ComputeContext& compute, SurfaceCache& surfaces, double max_circumradius) {
  auto sphere = [&](int agents) {
    return workload("sphere", max_circumradius, kBenchArea, agents, Integrator::Forward);
  };
  for (int agents : {100000, 1000000, 10000000}) throughput_line(compute, surfaces, sphere(agents), 0);
  for (int grouping : {1, 4}) throughput_line(compute, surfaces, sphere(1000000), grouping);
}

// Seconds per backward-Euler step of `field`, `per_wait` steps between waits for the device, each
// batch from the field u0 (so a long timing does not decay the field into zeros that solve for
// free); at least 0.3 s and three batches.
double seconds_per_step(const ComputeContext& compute, OpenCLDiffusionDecay& field, const DeviceVertexData<double>& u0,
                        int per_wait) {
  double elapsed = 0.0;
  int steps = 0;
  for (int batch = 0; batch < 3 || (elapsed < 0.3 && batch < 1000); ++batch) {
    field.set_concentration(u0);
    compute.queue.finish();
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < per_wait; ++s) field.step();
    compute.queue.finish();
    elapsed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    steps += per_wait;
  }
  return elapsed / steps;
}

// The backward-Euler pheromone step both ways the device can solve it, on the square (1,089
// vertices) and spheres (2,562 to 3.4 10^5 vertices; a 1.2M-vertex sphere's refinement and host
// factor took minutes on a lent GPU machine's CPU, and past 10^4 vertices CG wins by far), 4 m^2:
// the host factorization (on a device without native kernels, the field mapped: a copy each way
// per step) and device conjugate gradients. Each is checked against the
// reference after three steps from a varied field, then timed as lone steps (each waited for) and
// in batches of 32 (as a run issues them). The sizes where the host wins set
// DeviceTuning::host_implicit_solve_max_vertices for this kind of device.
void implicit_placement(const ComputeContext& compute, SurfaceCache& surfaces) {
  const Scene sc = scene(0, Integrator::Backward);
  // A 10 cm bound leaves the square's 32 x 32 cells as they are; the spheres' bounds refine them.
  const std::pair<const char*, double> surfaces_by_size[] = {{"square", 0.1},   {"sphere", 0.028}, {"sphere", 0.016},
                                                             {"sphere", 0.009}, {"sphere", 0.005}, {"sphere", 0.0028}};
  for (const auto& [shape, r] : surfaces_by_size) {
    const Workload w = workload(shape, r, kBenchArea, 0, Integrator::Backward);
    const SurfaceDomain domain = in_device_vertex_order(surfaces.get(w.surface).domain);
    const int n = domain.vertex_count;
    const VertexParameters params = VertexParameters::constant(sc.agent_model().parameters, n);
    std::vector<double> values(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) values[static_cast<size_t>(i)] = 0.1 + 0.9 * ((i * 37) % 101) / 100.0;
    const DeviceVertexData<double> u0(values);
    IntrinsicVertexData<double> want(values);
    ReferenceDiffusionDecay reference(domain, params, Integrator::Backward, sc.time_step);
    for (int s = 0; s < 3; ++s) reference.step(want);
    double scale = 0.0;
    for (const double v : want.values()) scale = std::max(scale, std::abs(v));
    double lone[2], batched[2];
    int iterations = 0;
    for (const ImplicitSolver solver : {ImplicitSolver::HostCholesky, ImplicitSolver::DeviceConjugateGradients}) {
      const int k = solver == ImplicitSolver::HostCholesky ? 0 : 1;
      OpenCLDiffusionDecayOptions options;
      options.implicit_solver = solver;
      OpenCLDiffusionDecay field(compute, domain, params, Integrator::Backward, sc.time_step, options);
      field.set_concentration(u0);
      for (int s = 0; s < 3; ++s) field.step();
      const DeviceVertexData<double> got = field.concentration();
      if (k == 1) iterations = field.last_solve().iterations;
      double diff = 0.0;
      for (int i = 0; i < n; ++i)
        diff = std::max(diff, std::abs(got[static_cast<size_t>(i)] - want[static_cast<size_t>(i)]));
      check(diff <= 1e-4 * scale, std::to_string(n) + " vertices, backward Euler, " +
                                      (k == 0 ? "host factor" : "device CG") + ": max difference " +
                                      std::to_string(diff) + " of " + std::to_string(scale));
      lone[k] = seconds_per_step(compute, field, u0, 1);
      batched[k] = seconds_per_step(compute, field, u0, 32);
    }
    std::printf("implicit step: %d vertices: host factor %.3f ms lone / %.3f ms in batches of 32; device CG %.3f / "
                "%.3f ms (%d iterations); host/CG %.2f / %.2f; the automatic choice: %s\n",
                n, 1e3 * lone[0], 1e3 * batched[0], 1e3 * lone[1], 1e3 * batched[1], iterations, lone[0] / lone[1],
                batched[0] / batched[1], implicit_solve_on_host(compute.device, n) ? "host" : "device CG");
  }
}

// The reaction-diffusion explicit step (Gray-Scott, two morphogens) on square grids of 10^4 to 10^6
// vertices: time per step, the bytes it must move per second, and that against the triad.
void reaction_diffusion(const ComputeContext& compute, double triad_bytes_per_second) {
  for (const int cells : {100, 316, 1000}) {
    const SurfaceDomain& domain = testing::grid_domain(cells);
    const ReactionDiffusionSystem s = testing::rough_gray_scott(domain, Integrator::Forward,
                                                                0.5 * testing::stable_step(domain, 2e-5));
    OpenCLReactionDiffusion rd(compute, domain, s);
    rd.run(2);
    rd.finish();
    const int steps = 200;
    const auto t0 = std::chrono::steady_clock::now();
    rd.run(steps);
    rd.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
    const double rate = rd.bytes_per_sub_step() / seconds;
    std::printf("reaction-diffusion explicit step: %d vertices, %.3g MB a step, %.4f ms/step, %.3g GB/s, %.2f of the "
                "triad\n",
                domain.vertex_count, rd.bytes_per_sub_step() / 1e6, 1e3 * seconds, rate / 1e9,
                rate / triad_bytes_per_second);
  }
}

int run(const std::string& device, const std::set<std::string>& sections) {
  const auto wanted = [&](const char* section) { return sections.empty() || sections.count(section) > 0; };
  const ComputeContext compute = make_compute_context(device);
  std::printf("device: %s\n", compute.device.describe().c_str());
  DeviceTriad triad(compute);
  const double bandwidth = triad.bytes_per_second(5);
  check(triad.result_is_correct(), "triad result");
  std::printf("memory bandwidth (triad, %.3g MB per triad): %.3g GB/s\n", triad.bytes_per_triad() / 1e6,
              bandwidth / 1e9);
  SurfaceCache surfaces;
  auto domain = [&](const Workload& w) -> const SurfaceDomain& { return surfaces.get(w.surface).domain; };
  if (wanted("checks")) {
    const Workload sphere = workload("sphere", 0.03, kBenchArea, 20000, Integrator::Forward);
    const Workload square = workload("square", 0.03, std::nullopt, 20000, Integrator::Backward);
    one_step(compute, domain(sphere), "sphere, forward Euler", Integrator::Forward);
    one_step(compute, domain(square), "square, backward Euler", Integrator::Backward);
    u_metric(compute, domain(sphere), "sphere, forward Euler", Integrator::Forward);
    u_metric(compute, domain(square), "square, backward Euler", Integrator::Backward);
    pheromone_forward(compute, domain(sphere), "sphere", bandwidth);
  }
  if (wanted("throughput")) {
    throughput(compute, surfaces, 0.015);
    throughput(compute, surfaces, 0.004);
    pheromone_forward(compute, domain(workload("sphere", 0.004, kBenchArea, 0, Integrator::Forward)),
                      "fine sphere", bandwidth);
    // Past the GPU's L2 (50 MB on an H100): ~1.3M vertices, ~90 MB per sub-step.
    throughput(compute, surfaces, 0.0015);
    pheromone_forward(compute, domain(workload("sphere", 0.0015, kBenchArea, 0, Integrator::Forward)),
                      "finest sphere", bandwidth);
  }
  if (wanted("implicit")) implicit_placement(compute, surfaces);
  if (wanted("rd")) reaction_diffusion(compute, bandwidth);
  std::printf("%d failed\n", testing::probe_failures());
  return testing::probe_exit_status();
}

}  // namespace
}  // namespace physarum::opencl

int main(int argc, char** argv) {
  std::string device;
  std::set<std::string> sections;
  const std::set<std::string> known = {"checks", "throughput", "implicit", "rd"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--device" || arg == "--only") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--device") {
        device = value;
        continue;
      }
      std::istringstream list(value);
      for (std::string section; std::getline(list, section, ',');) {
        if (!known.count(section)) {
          std::fprintf(stderr, "physarum_device_check: unknown section '%s' (checks, throughput, implicit, rd)\n",
                       section.c_str());
          return 2;
        }
        sections.insert(section);
      }
    } else {
      std::fprintf(stderr, "usage: physarum_device_check [--device SPEC] [--only SECTION[,SECTION...]]\n");
      return 2;
    }
  }
  try {
    return physarum::opencl::run(device, sections);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "physarum_device_check: error: %s\n", e.what());
    return 1;
  }
}
