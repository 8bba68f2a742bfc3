// `physarum bench [--device SPEC] [--quick] [--out DIR] [--meshes DIR]`: how the cost of a simulation
// step grows with the number of agents and with the surface's resolution, on both backends, in one
// run (so ratios are meaningful on a shared machine). Writes DIR/bench.json, DIR/bench.csv and
// log-log plots with fitted slopes (time per step against agents, against faces at fixed agents and
// against faces with the work per face held constant: agents.png, faces.png, faces_scaled.png;
// agent-steps per second: agents_throughput.png, faces_throughput.png), and prints a table, the
// paper-size case and a roofline estimate.
//
// The steps, in order: the agent sweep, the in-cache crossing rate, the resolution sweep (with the
// pheromone step alone at each resolution), the paper-size case, the roofline, the outputs. How a
// workload is timed lives in tools/bench/bench_session.hpp, the outputs in tools/bench/bench_report.hpp.
#include "common/base/errors.hpp"
#include "common/setup/workload.hpp"
#include "api/backend_factory.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/bench_session.hpp"
#include "tools/commands.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace physarum::cli {
namespace {

const std::vector<BackendChoice> kBackends = {BackendChoice::Reference, BackendChoice::OpenCL};

// spot.obj where the shared meshes are, else the built-in sphere.
std::string spot_or_sphere(const BenchSession& bench) {
  return bench.surface_spec("spot.obj").empty() ? "shape:sphere" : "spot.obj";
}

// Agent scaling at a fixed resolution; returns the surface it ran on.
std::string agent_sweep(BenchSession& bench) {
  const bool quick = bench.options().quick;
  const std::string agent_surface = spot_or_sphere(bench);
  const std::vector<int> agent_counts =
      quick ? std::vector<int>{1000, 10000, 100000} : std::vector<int>{1000, 10000, 100000, 1000000, 10000000};
  for (int n : agent_counts)
    for (const BackendChoice b : kBackends) {
      if (b == BackendChoice::Reference && n > 1000000) continue;  // ~5 s a step: the slope is clear without it
      bench.run("agents", bench.workload(agent_surface, 0.015, bench_scene(n), b));
    }
  return agent_surface;
}

// The in-cache crossing rate.
// The OpenCL issue's target: 10^8 face crossings/s on a mesh whose face records fit the cache, at
// about 24 crossings per agent-step. spot at 5 mm has 212k faces, 13.6 MB of face records (the
// L3 here is 32 MB). The default scene crosses ~12 faces per agent-step there; with its sensor
// distance and speed doubled, ~24, the operating point. Both, so the fixed per-agent cost
// (state, steering, deposits) shows beside the cost per crossing. The reference at 10^5 agents
// only: at 10^6 a step takes it several seconds.
void in_cache_sweep(BenchSession& bench) {
  const bool quick = bench.options().quick;
  const std::string surface = spot_or_sphere(bench);
  for (const bool doubled : {false, true}) {
    Scene scene = bench_scene(0);
    if (doubled) scene.agent_model().parameters[Param::sensor_distance] *= 2.0, scene.agent_model().parameters[Param::move_rate] *= 2.0;
    const std::string sweep = doubled ? "in_cache_x2" : "in_cache";
    for (const int agents : quick ? std::vector<int>{100000} : std::vector<int>{100000, 1000000})
      for (const BackendChoice b : kBackends) {
        if (b == BackendChoice::Reference && agents > 100000) continue;
        scene.agent_model().agents = agents;
        bench.run(sweep, bench.workload(surface, quick ? 0.01 : 0.005, scene, b));
      }
  }
}

// The pheromone step alone on one resolution, both backends and both integrators: one entry of
// bench.json's "pheromone_steps", printed as one line.
nlohmann::ordered_json pheromone_entry(BenchSession& bench, const std::string& surface, const SurfaceDomain& d) {
  nlohmann::ordered_json p = {{"surface", surface}, {"faces", d.face_count}, {"vertices", d.vertex_count}};
  for (const BackendChoice backend : kBackends) {
    const std::string b = to_string(backend);
    const PheromoneTiming forward = bench.pheromone_step(d, backend, Integrator::Forward);
    p[b + "_forward_seconds"] = forward.seconds;
    p["forward_sub_steps"] = forward.sub_steps;
    if (forward.bytes_per_step > 0.0) {
      p["opencl_forward_bytes"] = forward.bytes_per_step;
      p["triad_bytes_per_second"] = forward.triad_bytes_per_second;
      p["opencl_forward_fraction_of_triad"] = forward.bytes_per_step / forward.seconds / forward.triad_bytes_per_second;
    }
    p[b + "_backward_seconds"] = bench.pheromone_step(d, backend, Integrator::Backward).seconds;
  }
  std::printf("pheromone  %-18s %8d vertices  forward (%d sub-steps): opencl %.3f ms, %.3g GB/s = %.2f of the "
              "triad beside it (%.3g GB/s), reference %.3f ms; backward: opencl %.3f ms, reference %.3f ms\n",
              surface.c_str(), d.vertex_count, p["forward_sub_steps"].get<int>(),
              1e3 * p["opencl_forward_seconds"].get<double>(),
              p["opencl_forward_bytes"].get<double>() / p["opencl_forward_seconds"].get<double>() / 1e9,
              p["opencl_forward_fraction_of_triad"].get<double>(), p["triad_bytes_per_second"].get<double>() / 1e9,
              1e3 * p["reference_forward_seconds"].get<double>(), 1e3 * p["opencl_backward_seconds"].get<double>(),
              1e3 * p["reference_backward_seconds"].get<double>());
  std::fflush(stdout);
  return p;
}

// Resolution scaling at a fixed agent count (and with the work per face held constant), with the
// pheromone step alone at each resolution; returns bench.json's "pheromone_steps".
// Down to 2 mm: 1.3 million faces on spot and the sphere, past the 10^6 the out-of-cache
// target names.
nlohmann::ordered_json resolution_sweep(BenchSession& bench, int resolution_agents) {
  const BenchOptions& o = bench.options();
  const std::vector<double> radii = o.quick ? std::vector<double>{0.08, 0.04, 0.02, 0.01}
                                            : std::vector<double>{0.08, 0.04, 0.02, 0.01, 0.005, 0.0025, 0.002};
  const std::vector<std::string> surfaces =
      o.quick ? std::vector<std::string>{"shape:sphere"}
              : std::vector<std::string>{"spot.obj", "stanford-bunny.obj", "shape:sphere"};
  nlohmann::ordered_json pheromone = nlohmann::ordered_json::array();
  for (const std::string& surface : surfaces) {
    if (bench.surface_spec(surface).empty()) {
      std::printf("(skipping %s: not found under %s)\n", surface.c_str(), o.meshes.c_str());
      continue;
    }
    int previous_faces = -1;
    for (double radius : radii) {
      const SurfaceDomain* d = bench.domain(surface, radius);
      // A bound coarser than the input's own edges leaves it as it is: measure that mesh once.
      if (d->face_count == previous_faces) continue;
      previous_faces = d->face_count;
      for (const BackendChoice b : kBackends)
        bench.run("faces", bench.workload(surface, radius, bench_scene(resolution_agents), b));
      for (const BackendChoice b : kBackends)
        bench.run("faces_scaled", bench.workload(surface, radius, scene_scaled_to(*d), b));
      pheromone.push_back(pheromone_entry(bench, surface, *d));
    }
  }
  return pheromone;
}

// The paper-size case: 350,000 agents for 102 steps on a genus-1 mesh of ~46,000 faces.
nlohmann::ordered_json paper_case(BenchSession& bench) {
  double radius = 0.012;
  const SurfaceDomain* torus = bench.domain("shape:torus", radius);
  for (int i = 0; i < 6 && std::abs(torus->face_count - 46000) > 2000; ++i) {
    radius *= std::sqrt(static_cast<double>(torus->face_count) / 46000.0);
    torus = bench.domain("shape:torus", radius);
  }
  const std::unique_ptr<SimulationBackend> sim =
      make_backend(bench.workload("shape:torus", radius, bench_scene(350000), BackendChoice::OpenCL), bench.surfaces(),
                   &bench.compute());
  sim->finish();
  const Clock::time_point start = Clock::now();
  sim->run(102);
  sim->finish();
  const double seconds = seconds_since(start);
  std::printf("paper case: 350000 agents x 102 steps on a torus of %d faces: %.2f s (the paper: 17.6 s on 30 "
              "threads)\n",
              torus->face_count, seconds);
  return {{"agents", 350000}, {"steps", 102}, {"faces", torus->face_count}, {"seconds", seconds},
          {"paper_seconds_30_threads", 17.6}};
}

// The roofline estimate of the agent step (the last OpenCL row of the fixed-agent resolution sweep
// against agent_step_bytes, common/setup/workload.hpp: in cache the face records cost no DRAM traffic;
// this is the DRAM bound when nothing is reused) and of the forward pheromone step.
nlohmann::ordered_json roofline(BenchSession& bench, const nlohmann::ordered_json& pheromone) {
  const double bandwidth = bench.bandwidth().bytes_per_second(5);
  const Row* last = nullptr;
  for (const Row& r : bench.rows())
    if (r.sweep == "faces" && r.backend == "opencl") last = &r;
  nlohmann::ordered_json roofline = {{"memory_bandwidth_bytes_per_second", bandwidth},
                                     {"memory", bench.bandwidth().memory()}};
  if (last) {
    const double visits = agent_step_face_visits(last->crossings_per_agent_step);
    const double bytes = agent_step_bytes(last->crossings_per_agent_step);
    const double bound = bytes * last->agents / bandwidth;
    roofline["agent_step"] = {{"faces", last->faces},
                              {"bytes_per_agent_step", bytes},
                              {"random_accesses_per_agent_step", visits + 3 + 3},
                              {"bound_seconds_per_step", bound},
                              {"measured_seconds_per_step", last->seconds_per_step},
                              {"fraction_of_bound", bound / last->seconds_per_step}};
  }
  if (!pheromone.empty()) {
    // Forward Euler: each sub-step reads its matrix (hybrid ELL + CSR, 8 slots of 4 B column and
    // 4 B value per vertex) and u once and writes u once (opencl/diffusion_decay.hpp counts the bytes);
    // the neighbours' u it gathers are the cache's, not memory's. Each field against the triad
    // measured beside it; the last (largest) in detail, and the spread over the fields whose
    // sub-step moves more than the device's cache holds (as its driver reports it; where that is a
    // GPU's L1s, fields its L2 holds count too): smaller ones run partly from cache or wait on
    // kernel launches, and the memory bound does not apply to them.
    const auto& p = pheromone.back();
    const double cache_bytes = static_cast<double>(bench.compute().device.global_cache_bytes);
    const double bytes = p["opencl_forward_bytes"].get<double>();
    const double measured = p["opencl_forward_seconds"].get<double>();
    const double beside = p["triad_bytes_per_second"].get<double>();
    std::vector<double> fractions;
    for (const auto& q : pheromone)
      if (q["opencl_forward_bytes"].get<double>() / q["forward_sub_steps"].get<int>() > cache_bytes)
        fractions.push_back(q["opencl_forward_fraction_of_triad"].get<double>());
    std::sort(fractions.begin(), fractions.end());
    roofline["pheromone_forward_step"] = {{"vertices", p["vertices"]},
                                          {"sub_steps", p["forward_sub_steps"]},
                                          {"bytes_per_step", bytes},
                                          {"triad_beside_bytes_per_second", beside},
                                          {"bound_seconds_per_step", bytes / beside},
                                          {"measured_seconds_per_step", measured},
                                          {"fraction_of_bound", bytes / beside / measured},
                                          {"out_of_cache_fields", fractions.size()}};
    if (!fractions.empty()) {
      roofline["pheromone_forward_step"]["fraction_of_bound_out_of_cache_min"] = fractions.front();
      roofline["pheromone_forward_step"]["fraction_of_bound_out_of_cache_median"] = fractions[fractions.size() / 2];
    }
  }
  std::printf("roofline: memory bandwidth %.3g GB/s (%s); %s\n", bandwidth / 1e9, bench.bandwidth().memory(),
              roofline.dump().c_str());
  return roofline;
}

int run_bench(const BenchOptions& o) {
  BenchSession bench(o);
  std::printf("physarum bench on %s%s\n", bench.compute().device.describe().c_str(), o.quick ? " (quick)" : "");
  nlohmann::ordered_json report;
  report["device"] = bench.compute().device.describe();
  report["quick"] = o.quick;
  const std::string agent_surface = agent_sweep(bench);
  in_cache_sweep(bench);
  const int resolution_agents = o.quick ? 10000 : 100000;
  const nlohmann::ordered_json pheromone = resolution_sweep(bench, resolution_agents);
  report["pheromone_steps"] = pheromone;
  report["paper_case"] = paper_case(bench);
  report["roofline"] = roofline(bench, pheromone);
  write_bench_outputs(o.out, bench.rows(), agent_surface, resolution_agents, report);
  return 0;
}

}  // namespace

Command add_bench_command(CLI::App& parent) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* app = parent.add_subcommand(
      "bench", "Scaling benchmarks: time per step against agents and against faces, both backends, with plots");
  app->add_option("--device", options->device, "OpenCL device: index from `physarum devices` or a name substring");
  app->add_flag("--quick", options->quick, "Small sweeps (about two minutes), for frequent runs");
  app->add_option("--out", options->out, "Folder for bench.json, bench.csv and the plots (*.png)")
      ->capture_default_str();
  app->add_option("--meshes", options->meshes, "Folder of spot.obj and stanford-bunny.obj")->capture_default_str();
  return Command{app, [options] { return run_bench(*options); }};
}

}  // namespace physarum::cli
