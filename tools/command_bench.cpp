// `physarum bench [--device SPEC] [--quick] [--out DIR] [--meshes DIR]`: how the cost of a simulation
// step grows with the number of agents and with the surface's resolution, on both backends, in one
// run (so ratios are meaningful on a shared machine). Writes DIR/bench.json, DIR/bench.csv and
// log-log plots with fitted slopes (time per step against agents, against faces at fixed agents and
// against faces with the work per face held constant: agents.png, faces.png, faces_scaled.png;
// agent-steps per second: agents_throughput.png, faces_throughput.png), and prints a table, the
// paper-size case and a roofline estimate.
//
// What is timed: full steps (agents + pheromone) after three warm-up steps, until at least
// kMinSeconds have passed (and at least kMinSteps steps); the pheromone step alone (forward and
// backward Euler) on each resolution. The domain's preprocessing is not timed (bench_refinement
// covers it).
#include "bench/bench_support.hpp"
#include "common/atomic_write.hpp"
#include "common/errors.hpp"
#include "common/line_plot.hpp"
#include "common/memory_bandwidth.hpp"
#include "common/vertex_parameters.hpp"
#include "opencl/compute_context.hpp"
#include "opencl/device_tuning.hpp"
#include "opencl/face_records.hpp"
#include "opencl/memory_bandwidth.hpp"
#include "opencl/pheromone.hpp"
#include "opencl/simulation.hpp"
#include "reference/diffusion_decay.hpp"
#include "reference/simulation.hpp"
#include "tools/commands.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace physarum::cli {
namespace {

using bench::bench_scene;
using bench::scaled_domain;

struct BenchOptions {
  std::string device;
  bool quick = false;
  std::string out = "bench_out";
  std::string meshes = PHYSARUM_SHARED_MESHES;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct StepTiming {
  double seconds_per_step = 0.0;
  double crossings_per_agent_step = 0.0;
  long long steps = 0;
};

// Times steps of `sim` after a warm-up, for at least min_seconds and min_steps.
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

// Least-squares slope of log(y) against log(x) over the points with lo <= x <= hi.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (x[i] < lo || x[i] > hi || !(y[i] > 0)) continue;
    const double a = std::log(x[i]), b = std::log(y[i]);
    n += 1, sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  if (n < 2) return std::nan("");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The default scene rescaled to a domain so that the work per face is the same at every resolution.
// At fixed agents and fixed distances a finer mesh is not simply more of the same work: crossings
// per agent-step grow like 1/h ~ sqrt(F) (h the edge length) and forward Euler's sub-steps like
// 1/h^2 ~ F, so the fixed-agent sweep's slope in faces measures the model (about 0.5), not whether
// the implementation scales linearly. Here agents grow with F (one per face), lengths (sensor
// distance, speed) with h, and the diffusion rate with h^2: the same pattern in units of faces, with
// the same crossings per agent-step and sub-steps per step at every resolution, so a linear
// implementation takes time proportional to F (slope 1).
Scene scene_scaled_to(const SurfaceDomain& d) {
  constexpr double kNativeFaces = 20000;  // where the default scene's lengths are used as they are
  const double scale = std::sqrt(kNativeFaces / d.face_count);  // h over the native resolution's h
  Scene s = bench_scene(d.face_count);
  s.parameters[Param::sensor_distance] *= scale;
  s.parameters[Param::move_rate] *= scale;
  s.parameters[Param::diffuse_rate] *= scale * scale;
  return s;
}

// The bandwidth of the memory the kernels read, for the roofline: a triad on the device over arrays
// far larger than its cache, and for a CPU device (whose memory is the host's) the better of that
// and a triad on the host's threads, so the bound is the best rate this memory was seen to give.
class MemoryBandwidth {
 public:
  explicit MemoryBandwidth(const opencl::ComputeContext& compute) : device_(compute) {
    if (opencl::tuning_for(compute.device).host_triad) host_.emplace();
  }
  double bytes_per_second(int repeats) {
    const double device = device_.bytes_per_second(repeats);
    return host_ ? std::max(device, host_->bytes_per_second(repeats)) : device;
  }
  const char* memory() const {
    return host_ ? "host memory: the better of an OpenCL and a host triad" : "device memory: OpenCL triad";
  }

 private:
  opencl::DeviceTriad device_;
  std::optional<HostTriad> host_;
};

struct Row {
  std::string sweep, surface, backend;
  int agents = 0, faces = 0, vertices = 0;
  double seconds_per_step = 0, agent_steps_per_second = 0, crossings_per_agent_step = 0, crossings_per_second = 0;
};

nlohmann::ordered_json to_json(const Row& r) {
  return {{"sweep", r.sweep}, {"surface", r.surface}, {"backend", r.backend}, {"agents", r.agents},
          {"faces", r.faces}, {"vertices", r.vertices}, {"seconds_per_step", r.seconds_per_step},
          {"agent_steps_per_second", r.agent_steps_per_second},
          {"crossings_per_agent_step", r.crossings_per_agent_step}, {"crossings_per_second", r.crossings_per_second}};
}

class Bench {
 public:
  Bench(const BenchOptions& o)
      : options_(o), compute_(opencl::make_compute_context(o.device)), bandwidth_(compute_) {}

  std::string surface_spec(const std::string& name) const {
    if (name.rfind("shape:", 0) == 0) return name;
    const std::filesystem::path p = std::filesystem::path(options_.meshes) / name;
    return std::filesystem::exists(p) ? p.string() : "";
  }

  const SurfaceDomain* domain(const std::string& surface, double max_circumradius) {
    const std::string spec = surface_spec(surface);
    if (spec.empty()) return nullptr;
    return scaled_domain(spec, max_circumradius);
  }

  Row run(const std::string& sweep, const std::string& surface, const SurfaceDomain& d, const std::string& backend,
          const Scene& scene) {
    const double min_seconds = options_.quick ? 0.15 : 0.6;
    const int agents = scene.agents;
    std::unique_ptr<SimulationBackend> sim;
    if (backend == "opencl") sim = std::make_unique<opencl::OpenCLSimulation>(compute_, d, scene);
    else sim = std::make_unique<ReferenceSimulation>(d, scene);
    const StepTiming t = time_steps(*sim, min_seconds, 3, 1000);
    Row r{sweep, surface, backend, agents, d.face_count, d.vertex_count, t.seconds_per_step,
          agents / t.seconds_per_step, t.crossings_per_agent_step, 0.0};
    r.crossings_per_second = r.agent_steps_per_second * r.crossings_per_agent_step;
    std::printf("%-12s %-18s %-9s %9d agents %8d faces  %9.3f ms/step  %8.3g agent-steps/s  %5.1f crossings/step  "
                "%8.3g crossings/s\n",
                sweep.c_str(), surface.c_str(), backend.c_str(), agents, d.face_count, 1e3 * t.seconds_per_step,
                r.agent_steps_per_second, r.crossings_per_agent_step, r.crossings_per_second);
    std::fflush(stdout);
    rows_.push_back(r);
    return r;
  }

  // The pheromone step alone: seconds per step (the best of several) and the forward-Euler sub-steps
  // each step takes. OpenCL's forward Euler alternates its steps with triads, so the bandwidth it is
  // compared with was measured in the same seconds, by the best of as many tries.
  struct PheromoneTiming {
    double seconds = 0.0;
    int sub_steps = 1;
    double bytes_per_step = 0.0;         // OpenCL forward Euler: what its sub-steps read and write
    double triad_bytes_per_second = 0.0;  // OpenCL forward Euler: the triad beside it
  };
  PheromoneTiming pheromone_step(const SurfaceDomain& d, const std::string& backend, Integrator integrator) {
    const Scene scene = bench_scene(0);
    const VertexParameters params = VertexParameters::constant(scene.parameters, d.vertex_count);
    PheromoneTiming t;
    auto time = [&](auto step, auto finish, bool beside_triad) {
      step();
      finish();
      // The best of several single steps: on a shared machine the best is what the code can do,
      // the rest is other tenants.
      const Clock::time_point start = Clock::now();
      double best = INFINITY;
      for (int steps = 0; steps < 5 || (steps < 30 && seconds_since(start) < 0.3); ++steps) {
        if (beside_triad)
          t.triad_bytes_per_second = std::max(t.triad_bytes_per_second, bandwidth_.bytes_per_second(1));
        const Clock::time_point step_start = Clock::now();
        step();
        finish();
        best = std::min(best, seconds_since(step_start));
      }
      return best;
    };
    if (backend == "opencl") {
      // Numbered as a simulation numbers the device's field, so it reads memory the same way.
      opencl::OpenCLPheromone field(compute_, opencl::in_device_vertex_order(d), params, integrator, scene.time_step);
      const bool forward = integrator == Integrator::ForwardEuler;
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

  MemoryBandwidth& bandwidth() { return bandwidth_; }
  const std::vector<Row>& rows() const { return rows_; }
  const opencl::ComputeContext& compute() const { return compute_; }
  const BenchOptions& options() const { return options_; }

 private:
  BenchOptions options_;
  opencl::ComputeContext compute_;
  std::vector<Row> rows_;
  MemoryBandwidth bandwidth_;
};

// Draws one sweep (a line per surface and backend), seconds per step or agent-steps per second
// against agents or faces, and returns the fitted log-log slopes.
enum class Axis { kAgents, kFaces };
enum class Measure { kSecondsPerStep, kAgentStepsPerSecond };
nlohmann::ordered_json plot(const std::string& path, const std::vector<Row>& rows, const std::string& sweep,
                            Axis axis, Measure measure, const std::string& title) {
  nlohmann::ordered_json slopes = nlohmann::ordered_json::array();
  std::vector<PlotSeries> series;
  const std::array<std::array<float, 3>, 6> colors = {{{0.12f, 0.35f, 0.75f},
                                                        {0.85f, 0.35f, 0.1f},
                                                        {0.2f, 0.6f, 0.2f},
                                                        {0.6f, 0.2f, 0.6f},
                                                        {0.5f, 0.5f, 0.1f},
                                                        {0.1f, 0.6f, 0.6f}}};
  std::vector<std::pair<std::string, std::string>> keys;
  for (const Row& r : rows)
    if (r.sweep == sweep && std::find(keys.begin(), keys.end(), std::make_pair(r.surface, r.backend)) == keys.end())
      keys.emplace_back(r.surface, r.backend);
  for (size_t k = 0; k < keys.size(); ++k) {
    PlotSeries s;
    s.color = colors[k % colors.size()];
    s.dashed = keys[k].second == "reference";
    std::vector<double> x, y;
    for (const Row& r : rows)
      if (r.sweep == sweep && r.surface == keys[k].first && r.backend == keys[k].second) {
        x.push_back(axis == Axis::kAgents ? r.agents : r.faces);
        y.push_back(measure == Measure::kSecondsPerStep ? r.seconds_per_step : r.agent_steps_per_second);
      }
    // The ranges (1e5..1e7 agents, 1e4..1e6 faces); a quick run fits whatever it has.
    double slope = axis == Axis::kAgents ? log_log_slope(x, y, 1e5, 1e7) : log_log_slope(x, y, 1e4, 1e6);
    if (std::isnan(slope)) slope = log_log_slope(x, y, 0.0, 1e300);
    char label[96];
    std::snprintf(label, sizeof label, "%s %s, slope %.2f", keys[k].first.c_str(), keys[k].second.c_str(), slope);
    s.label = label;
    slopes.push_back({{"surface", keys[k].first}, {"backend", keys[k].second}, {"slope", slope}});
    s.x = x;
    s.y = y;
    series.push_back(std::move(s));
  }
  if (series.empty()) return slopes;
  PlotOptions o;
  o.log_x = o.log_y = true;
  o.width = 1000;
  o.title = title;
  o.x_label = axis == Axis::kAgents ? "agents" : "intrinsic faces";
  o.y_label = measure == Measure::kSecondsPerStep ? "seconds per step" : "agent-steps per second";
  write_line_plot_png(path, series, o);
  return slopes;
}

int run_bench(const BenchOptions& o) {
  Bench bench(o);
  std::printf("physarum bench on %s%s\n", bench.compute().device.describe().c_str(), o.quick ? " (quick)" : "");
  const std::vector<std::string> backends = {"reference", "opencl"};
  nlohmann::ordered_json report;
  report["device"] = bench.compute().device.describe();
  report["quick"] = o.quick;

  // ---- agent scaling at a fixed resolution ----
  const std::string agent_surface = bench.surface_spec("spot.obj").empty() ? "shape:sphere" : "spot.obj";
  const SurfaceDomain* fixed = bench.domain(agent_surface, 0.015);
  const std::vector<int> agent_counts =
      o.quick ? std::vector<int>{1000, 10000, 100000} : std::vector<int>{1000, 10000, 100000, 1000000, 10000000};
  for (int n : agent_counts)
    for (const std::string& b : backends) {
      if (b == "reference" && n > 1000000) continue;  // ~5 s a step: the slope is clear without it
      bench.run("agents", agent_surface, *fixed, b, bench_scene(n));
    }

  // ---- the in-cache crossing rate ----
  // The OpenCL issue's target: 10^8 face crossings/s on a mesh whose face records fit the cache, at
  // about 24 crossings per agent-step. spot at 5 mm has 212k faces, 13.6 MB of face records (the
  // L3 here is 32 MB). The default scene crosses ~12 faces per agent-step there; with its sensor
  // distance and speed doubled, ~24, the operating point. Both, so the fixed per-agent cost
  // (state, steering, deposits) shows beside the cost per crossing. The reference at 10^5 agents
  // only: at 10^6 a step takes it several seconds.
  {
    const std::string surface = bench.surface_spec("spot.obj").empty() ? "shape:sphere" : "spot.obj";
    const SurfaceDomain* cached = bench.domain(surface, o.quick ? 0.01 : 0.005);
    for (const bool doubled : {false, true}) {
      Scene scene = bench_scene(0);
      if (doubled) scene.parameters[Param::sensor_distance] *= 2.0, scene.parameters[Param::move_rate] *= 2.0;
      const std::string sweep = doubled ? "in_cache_x2" : "in_cache";
      for (const int agents : o.quick ? std::vector<int>{100000} : std::vector<int>{100000, 1000000})
        for (const std::string& b : backends) {
          if (b == "reference" && agents > 100000) continue;
          scene.agents = agents;
          bench.run(sweep, surface, *cached, b, scene);
        }
    }
  }

  // ---- resolution scaling at a fixed agent count ----
  // Down to 2 mm: 1.3 million faces on spot and the sphere, past the 10^6 the out-of-cache
  // target names.
  const std::vector<double> radii = o.quick ? std::vector<double>{0.08, 0.04, 0.02, 0.01}
                                            : std::vector<double>{0.08, 0.04, 0.02, 0.01, 0.005, 0.0025, 0.002};
  const std::vector<std::string> surfaces =
      o.quick ? std::vector<std::string>{"shape:sphere"}
              : std::vector<std::string>{"spot.obj", "stanford-bunny.obj", "shape:sphere"};
  const int resolution_agents = o.quick ? 10000 : 100000;
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
      for (const std::string& b : backends) bench.run("faces", surface, *d, b, bench_scene(resolution_agents));
      for (const std::string& b : backends) bench.run("faces_scaled", surface, *d, b, scene_scaled_to(*d));
      nlohmann::ordered_json p = {{"surface", surface}, {"faces", d->face_count}, {"vertices", d->vertex_count}};
      for (const std::string& b : backends) {
        const auto forward = bench.pheromone_step(*d, b, Integrator::ForwardEuler);
        p[b + "_forward_seconds"] = forward.seconds;
        p["forward_sub_steps"] = forward.sub_steps;
        if (forward.bytes_per_step > 0.0) {
          p["opencl_forward_bytes"] = forward.bytes_per_step;
          p["triad_bytes_per_second"] = forward.triad_bytes_per_second;
          p["opencl_forward_fraction_of_triad"] =
              forward.bytes_per_step / forward.seconds / forward.triad_bytes_per_second;
        }
        p[b + "_backward_seconds"] = bench.pheromone_step(*d, b, Integrator::BackwardEuler).seconds;
      }
      std::printf("pheromone  %-18s %8d vertices  forward (%d sub-steps): opencl %.3f ms, %.3g GB/s = %.2f of the "
                  "triad beside it (%.3g GB/s), reference %.3f ms; backward: opencl %.3f ms, reference %.3f ms\n",
                  surface.c_str(), d->vertex_count, p["forward_sub_steps"].get<int>(),
                  1e3 * p["opencl_forward_seconds"].get<double>(),
                  p["opencl_forward_bytes"].get<double>() / p["opencl_forward_seconds"].get<double>() / 1e9,
                  p["opencl_forward_fraction_of_triad"].get<double>(), p["triad_bytes_per_second"].get<double>() / 1e9,
                  1e3 * p["reference_forward_seconds"].get<double>(), 1e3 * p["opencl_backward_seconds"].get<double>(),
                  1e3 * p["reference_backward_seconds"].get<double>());
      std::fflush(stdout);
      pheromone.push_back(p);
    }
  }
  report["pheromone_steps"] = pheromone;

  // ---- the paper-size case: 350,000 agents for 102 steps on a genus-1 mesh of ~46,000 faces ----
  {
    double radius = 0.012;
    const SurfaceDomain* torus = bench.domain("shape:torus", radius);
    for (int i = 0; i < 6 && std::abs(torus->face_count - 46000) > 2000; ++i) {
      radius *= std::sqrt(static_cast<double>(torus->face_count) / 46000.0);
      torus = bench.domain("shape:torus", radius);
    }
    const Scene scene = bench_scene(350000);
    opencl::OpenCLSimulation sim(bench.compute(), *torus, scene);
    sim.finish();
    const Clock::time_point start = Clock::now();
    sim.run(102);
    sim.finish();
    const double seconds = seconds_since(start);
    std::printf("paper case: 350000 agents x 102 steps on a torus of %d faces: %.2f s (the paper: 17.6 s on 30 "
                "threads)\n",
                torus->face_count, seconds);
    report["paper_case"] = {{"agents", 350000}, {"steps", 102}, {"faces", torus->face_count}, {"seconds", seconds},
                            {"paper_seconds_30_threads", 17.6}};
  }

  // ---- roofline estimate ----
  const double bandwidth = bench.bandwidth().bytes_per_second(5);
  {
    // Agent step: state read and written (face 4, position 8, heading 8, five floats 20, id 4 = 44 B
    // each way), one 64-byte face record per face visited, three concentration reads per sensor
    // and three 8-byte deposit atomics per movement piece. In cache the records cost no DRAM
    // traffic; this is the DRAM bound when nothing is reused.
    const Row* last = nullptr;
    for (const Row& r : bench.rows())
      if (r.sweep == "faces" && r.backend == "opencl") last = &r;
    nlohmann::ordered_json roofline = {{"memory_bandwidth_bytes_per_second", bandwidth},
                                       {"memory", bench.bandwidth().memory()}};
    if (last) {
      const double visits = last->crossings_per_agent_step + 1.6;  // + one start face per walk (1 move + 3/5 sensing)
      const double bytes = 88.0 + 64.0 * visits + 4.0 * 9.0 * 0.6 + 24.0;
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
      // 4 B value per vertex) and u once and writes u once (opencl/pheromone.hpp counts the bytes);
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
    report["roofline"] = roofline;
    std::printf("roofline: memory bandwidth %.3g GB/s (%s); %s\n", bandwidth / 1e9, bench.bandwidth().memory(),
                roofline.dump().c_str());
  }

  // ---- slopes and outputs ----
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const Row& r : bench.rows()) rows.push_back(to_json(r));
  report["rows"] = rows;
  create_output_folder(o.out);
  const std::filesystem::path out(o.out);
  std::ostringstream csv;
  csv << "sweep,surface,backend,agents,faces,vertices,seconds_per_step,agent_steps_per_second,"
         "crossings_per_agent_step,crossings_per_second\n";
  csv.precision(9);
  for (const Row& r : bench.rows())
    csv << r.sweep << "," << r.surface << "," << r.backend << "," << r.agents << "," << r.faces << "," << r.vertices
        << "," << r.seconds_per_step << "," << r.agent_steps_per_second << "," << r.crossings_per_agent_step << ","
        << r.crossings_per_second << "\n";
  write_text_file_atomically((out / "bench.csv").string(), csv.str());
  // Slopes of time per step (those of agent-steps per second follow from them).
  const auto png = [&](const char* name) { return (out / name).string(); };
  const std::string fixed_agents = " (" + std::to_string(resolution_agents) + " agents)";
  report["slopes"] = {
      {"agents", plot(png("agents.png"), bench.rows(), "agents", Axis::kAgents, Measure::kSecondsPerStep,
                      "Time per step against agents (" + agent_surface + ")")},
      {"faces", plot(png("faces.png"), bench.rows(), "faces", Axis::kFaces, Measure::kSecondsPerStep,
                     "Time per step against intrinsic faces" + fixed_agents)},
      {"faces_scaled", plot(png("faces_scaled.png"), bench.rows(), "faces_scaled", Axis::kFaces,
                            Measure::kSecondsPerStep,
                            "Time per step against intrinsic faces, work per face held constant")}};
  plot(png("agents_throughput.png"), bench.rows(), "agents", Axis::kAgents, Measure::kAgentStepsPerSecond,
       "Agent-steps per second against agents (" + agent_surface + ")");
  plot(png("faces_throughput.png"), bench.rows(), "faces", Axis::kFaces, Measure::kAgentStepsPerSecond,
       "Agent-steps per second against intrinsic faces" + fixed_agents);
  std::printf("fitted log-log slopes of time per step: %s\n", report["slopes"].dump().c_str());
  write_text_file_atomically((out / "bench.json").string(), report.dump(2) + "\n");
  std::printf("wrote %s/{bench.json, bench.csv, agents.png, faces.png, faces_scaled.png, agents_throughput.png, "
              "faces_throughput.png}\n",
              out.string().c_str());
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
