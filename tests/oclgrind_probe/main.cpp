// Runs every kernel of the agent, pheromone, reaction-diffusion and statistics programs (competing species'
// included, and philox_check.cl) once on a small problem, for tests/test_oclgrind.cpp, which runs this program under oclgrind's race, memory and
// API checks. Exit 0 when every run finished and every canary is intact.
//
//   physarum_oclgrind_probe               the clean run
//   physarum_oclgrind_probe --fault-demo  a kernel that writes one element past its buffer: proves
//                                         the oclgrind check can fail
#include "common/setup/agent_inputs.hpp"
#include "common/base/errors.hpp"
#include "delaunay_domain.hpp"
#include "kernels/device_types.h"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/diffusion_decay.hpp"
#include "opencl/agent_simulation.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/reaction_diffusion.hpp"
#include "pheromone_rates.hpp"
#include "pheromone_test_meshes.hpp"
#include "probe_checks.hpp"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

namespace physarum::opencl {
namespace {

using testing::check;
using testing::uniform_rates;

DeviceVertexData<double> ramp(int n) {
  DeviceVertexData<double> u(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) u[static_cast<size_t>(i)] = 0.1 + 0.9 * ((i * 37) % 101) / 100.0;
  return u;
}

// The agent parameters every agent run below shares; only the speed differs between runs. With
// the runs' time step of 0.02 s, turn_frequency 120 is 2.4 decisions per step: the first sensed
// ahead of the step, the rest inside it; the short lifetime makes agents respawn within the run.
void set_agent_parameters(ParameterValues& p, double move_rate) {
  p[Param::sensor_distance] = 0.3;
  p[Param::sensor_angle] = 0.4;
  p[Param::move_rate] = move_rate;
  p[Param::turn_rate] = 3.0;
  p[Param::turn_frequency] = 120.0;
  p[Param::deposit_rate] = 1.0;
  p[Param::decay_rate] = 0.5;
  p[Param::diffuse_rate] = 0.01;
  p[Param::mean_lifetime] = 0.05;
  p[Param::activation_time] = 0.01;
}

// One check that no kernel wrote into a canary region, naming the damaged buffers when one did.
void check_canaries_intact(const std::vector<std::string>& damaged, const std::string& label) {
  std::string names;
  for (const auto& name : damaged) names += " " + name;
  check(damaged.empty(), label + ": canaries intact" + names);
}

void run_pheromone(const ComputeContext& compute, const SurfaceDomain& domain, const VertexParameters& params,
                   Integrator integrator, double dt, const std::string& label) {
  OpenCLDiffusionDecayOptions options;
  options.implicit_solver = ImplicitSolver::DeviceConjugateGradients;  // the CG kernels are under test
  options.cg_max_iterations = 64;  // oclgrind interprets every work-item: keep the solve short
  options.cg_check_interval = 8;
  OpenCLDiffusionDecay field(compute, domain, params, integrator, dt, options);
  field.set_concentration(ramp(domain.vertex_count));
  field.add_deposits(DeviceVertexData<double>(static_cast<size_t>(domain.vertex_count), 1e-3));
  for (int s = 0; s < 2; ++s) field.step();
  const FieldStatistics stats = field.statistics(0.5);
  const double total = field.total_amount();
  const DeviceVertexData<double> u = field.concentration();
  bool finite = std::isfinite(stats.mean) && std::isfinite(total);
  for (double x : u) finite = finite && std::isfinite(x);
  check(finite, label + ": field and statistics finite (mean " + std::to_string(stats.mean) + ", " +
                    std::to_string(field.sub_steps()) + " sub-steps, " +
                    std::to_string(field.last_solve().iterations) + " CG iterations)");
  check_canaries_intact(field.damaged_canaries(), label);
}

// A few hundred agents for a few steps: initialise_agents, agent_step (sensing, steering, moving,
// reflecting, depositing, respawning) and pheromone_add_deposits, on a closed surface and on one
// with a boundary, with scalar walks (one agent per work-item, as on GPUs) and with vector-lane walks
// (four agents a walker, three walkers a work-item, as on CPUs). Several turn decisions every step
// and a short lifetime make every branch run.
void run_agents(const ComputeContext& compute, const SurfaceDomain& domain, Integrator integrator,
                int agents_per_work_item, const std::string& label) {
  Scene scene;
  scene.agent_model().agents = 301;  // not a multiple of the work-group size or of 4: padded and part-filled work-items run too
  scene.time_step = 0.02;
  // move_rate 10: several faces per step, and boundary hits on the square
  set_agent_parameters(scene.agent_model().parameters, 10.0);
  scene.agent_model().integrator = integrator;
  OpenCLBackendOptions options;
  options.agents_per_work_item = agents_per_work_item;
  options.pheromone.cg_max_iterations = 64;
  options.pheromone.cg_check_interval = 8;
  OpenCLAgentSimulation sim(compute, domain, constant_parameters(scene, domain), simulation_settings(scene), options);
  sim.run(3);
  const SimulationCounters c = sim.counters();
  const FieldStatistics stats = sim.field_statistics(1.0);
  check(std::isfinite(stats.mean) && stats.mean > 0.0 && c.respawns > 0 && c.face_crossings > 0,
        label + ": agents moved (" + std::to_string(c.face_crossings) + " crossings, " +
            std::to_string(c.boundary_hits) + " boundary hits, " + std::to_string(c.respawns) + " respawns), mean " +
            std::to_string(stats.mean));
  check_canaries_intact(sim.damaged_canaries(), label);
}

// The same agents with every control of Sec. 3.3 switched on (common/model/simulation_controls.hpp), so
// their kernel paths run under the checker too: a read-stimulus and a write rate (with negative
// values, clamped), spawn weights with a zero region and a sink (mean lifetime 0), a bias of
// symmetry 3 with spawn headings along it and a zero-direction face, a terminating boundary on the
// square, and varying agent parameters (no uniform fast path).
void run_agents_with_controls(const ComputeContext& compute, const SurfaceDomain& domain, Integrator integrator,
                              int agents_per_work_item, const std::string& label) {
  const int n = domain.vertex_count;
  Scene scene;
  set_agent_parameters(scene.agent_model().parameters, 10.0);
  VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, n);
  SimulationControls controls;
  controls.read_stimulus.assign(static_cast<size_t>(n), 0.0);
  controls.write_rate.assign(static_cast<size_t>(n), 0.0);
  controls.spawn_weight.assign(static_cast<size_t>(n), 0.0);
  DirectionalBias bias;
  bias.symmetry = 3;
  bias.strength.assign(static_cast<size_t>(n), 0.0);
  bias.direction.assign(static_cast<size_t>(domain.face_count), {1.0, 0.5});
  bias.direction[0] = {0.0, 0.0};
  for (int i = 0; i < n; ++i) {
    const auto v = static_cast<size_t>(i);
    params[Param::move_rate][v] = 5.0 + 0.1 * (i % 7);
    if (i == n / 2) params[Param::mean_lifetime][v] = 0.0;  // a sink
    controls.read_stimulus[v] = (i % 3 == 0) ? 0.5 : -0.25;
    controls.write_rate[v] = (i % 4 == 0) ? -1.0 : 0.5;
    controls.spawn_weight[v] = (i < n / 4) ? 0.0 : 1.0 + (i % 5);
    bias.strength[v] = 2.0 + 0.01 * i;
  }
  controls.bias = bias;
  controls.spawn_heading = SpawnHeading::Bias;
  controls.boundary = BoundaryBehaviour::Terminate;
  SimulationSettings settings;
  settings.agents = 301;
  settings.time_step = 0.02;
  settings.seed = 5;
  settings.integrator = integrator;
  OpenCLBackendOptions options;
  options.agents_per_work_item = agents_per_work_item;
  options.pheromone.cg_max_iterations = 64;
  options.pheromone.cg_check_interval = 8;
  OpenCLAgentSimulation sim(compute, domain, params, controls, settings, options);
  sim.run(3);
  const SimulationCounters c = sim.counters();
  const FieldStatistics stats = sim.field_statistics(1.0);
  check(std::isfinite(stats.mean) && stats.mean > 0.0 && c.respawns > 0,
        label + ": agents moved with controls (" + std::to_string(c.respawns) + " respawns), mean " +
            std::to_string(stats.mean));
  check_canaries_intact(sim.damaged_canaries(), label);
}

// Three competing species (kernels/species.cl: -DPHYSARUM_SPECIES=3) of uneven sizes with their own
// varying parameters, an asymmetric matrix with a negative entry, a read-stimulus and a write rate,
// on a terminating boundary where the domain has one: every species path of the agent kernels, the
// sensed-field kernel and the per-species deposit sub-buffers under the checker.
void run_competing_species(const ComputeContext& compute, const SurfaceDomain& domain, int agents_per_work_item,
                           const std::string& label) {
  const int n = domain.vertex_count;
  Scene scene;
  set_agent_parameters(scene.agent_model().parameters, 8.0);
  SpeciesSet species;
  const int sizes[3] = {101, 57, 143};
  for (int s = 0; s < 3; ++s) {
    VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, n);
    for (int i = 0; i < n; ++i) {
      params[Param::move_rate][static_cast<size_t>(i)] = 4.0 + s + 0.1 * (i % 7);
      params[Param::decay_rate][static_cast<size_t>(i)] = 0.5 + 0.25 * s;
    }
    species.species.push_back(Species{sizes[s], params});
  }
  species.sensing = {1.0, -0.5, 0.2, 0.0, 1.0, -1.0, 0.7, 0.0, 1.0};
  SimulationControls controls;
  controls.read_stimulus.assign(static_cast<size_t>(n), 0.0);
  controls.write_rate.assign(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    controls.read_stimulus[static_cast<size_t>(i)] = (i % 3 == 0) ? 0.5 : -0.25;
    controls.write_rate[static_cast<size_t>(i)] = (i % 4 == 0) ? 0.25 : 0.0;
  }
  controls.boundary = BoundaryBehaviour::Terminate;
  SimulationSettings settings;
  settings.agents = 301;
  settings.time_step = 0.02;
  settings.seed = 9;
  OpenCLBackendOptions options;
  options.agents_per_work_item = agents_per_work_item;
  OpenCLAgentSimulation sim(compute, domain, species, controls, settings, options);
  sim.run(3);
  check(sim.dynamic_layer_count() == 3, label + ": one layer per species");
  for (int layer = 0; layer < 3; ++layer) {
    const FieldStatistics stats = sim.field_statistics(1.0, layer);
    check(std::isfinite(stats.mean) && stats.mean > 0.0,
          label + ": layer " + std::to_string(layer) + " mean " + std::to_string(stats.mean));
  }
  check_canaries_intact(sim.damaged_canaries(), label);
}

void run_philox(const ComputeContext& compute) {
  const cl::Program p = build_program(compute.context, compute.device, "philox_check.cl", kernel_source("philox_check.cl"));
  const cl_uint n = 3;
  std::vector<cl_uint4> counters(n, cl_uint4{{1, 2, 3, 4}});
  std::vector<cl_uint2> keys(n, cl_uint2{{5, 6}});
  cl::Buffer bc(compute.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(cl_uint4), counters.data());
  cl::Buffer bk(compute.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(cl_uint2), keys.data());
  cl::Buffer br(compute.context, CL_MEM_WRITE_ONLY, n * sizeof(cl_uint4));
  cl::Kernel k(p, "philox_known_answers");
  set_arguments_checked(k, bc, bk, br, n);
  compute.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  std::vector<cl_uint4> results(n);
  compute.queue.enqueueReadBuffer(br, CL_TRUE, 0, n * sizeof(cl_uint4), results.data());
  check(results[0].s[0] == results[2].s[0], "philox_check.cl: equal inputs give equal outputs");
}

// The deliberate fault: work-item i writes x[i + 1], so the last one writes past the buffer.
void run_fault_demo(const ComputeContext& compute) {
  const char* source = "__kernel void off_by_one(__global float* x, const uint n) {\n"
                       "  const uint i = get_global_id(0);\n"
                       "  if (i >= n) return;\n"
                       "  x[i + 1] = 1.0f;\n"
                       "}\n";
  const cl::Program p = build_program(compute.context, compute.device, "fault_demo.cl", source);
  const cl_uint n = 16;
  cl::Buffer x(compute.context, CL_MEM_READ_WRITE, n * sizeof(float));
  cl::Kernel k(p, "off_by_one");
  set_arguments_checked(k, x, n);
  compute.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  compute.queue.finish();
  check(true, "fault demo ran (oclgrind must report an invalid write)");
}

// Gray-Scott with F varying per vertex (a coefficient buffer), every fifth vertex held (the
// Dirichlet paths), two explicit sub-steps (the double buffer both ways; shared or per-morphogen
// weights) or two IMEX steps with the device's conjugate gradients. With `morphogens` > 2, linear
// morphogens w, x, ... follow u (w' = 0.5 u - w, x' = 0.2 w - 0.4 x, ...): five or more take the
// kernel's eight-lane vector path.
void run_reaction_diffusion(const ComputeContext& compute, const SurfaceDomain& domain, Integrator integrator,
                            const std::string& label, bool proportional_stiffness = true, int morphogens = 2) {
  const int n = domain.vertex_count;
  const size_t un = static_cast<size_t>(n);
  ReactionDiffusionSystem s;
  s.morphogens = {"u", "v"};
  s.reaction = {"-u*v^2 + F*(1-u)", "u*v^2 - (F+k)*v"};
  s.coefficient_names = {"F", "k"};
  s.coefficients = {IntrinsicVertexData<double>(un), IntrinsicVertexData<double>(un, 0.06)};
  s.initial = {IntrinsicVertexData<double>(un), IntrinsicVertexData<double>(un)};
  s.fixed.assign(un, 0);
  for (int i = 0; i < n; ++i) {
    s.coefficients[0][static_cast<size_t>(i)] = 0.03 + 0.0001 * (i % 50);
    s.initial[0][static_cast<size_t>(i)] = 1.0 - 0.5 * ((i * 37) % 101) / 100.0;
    s.initial[1][static_cast<size_t>(i)] = 0.25 * ((i * 53) % 97) / 96.0;
    if (i % 5 == 0) s.fixed[static_cast<size_t>(i)] = 1;
  }
  for (double D : {2e-3, 1e-3}) {
    CsrMatrix K = domain.laplacian;
    for (double& v : K.value) v *= D;
    s.stiffness.push_back(K);
  }
  const std::vector<std::string> extra = {"w", "x", "y", "z", "p", "q"};
  for (int m = 2; m < morphogens; ++m) {
    const std::string& name = extra[static_cast<size_t>(m - 2)];
    s.morphogens.push_back(name);
    s.reaction.push_back(m == 2 ? "0.5*u - w" : "0.2*" + extra[static_cast<size_t>(m - 3)] + " - 0.4*" + name);
    s.initial.emplace_back(un, 0.1 * m);
    CsrMatrix K = s.stiffness[0];  // a copy first: push_back may move the vector it reads from
    for (double& v : K.value) v *= 0.3 + 0.1 * m;
    s.stiffness.push_back(std::move(K));
  }
  // Not multiples of one another (as anisotropy makes them): each morphogen's own weights.
  if (!proportional_stiffness)
    for (size_t e = 0; e < s.stiffness.back().value.size(); ++e) s.stiffness.back().value[e] *= 1.0 + 0.5 * ((e * 7) % 3);
  s.mass = domain.vertex_mass;
  s.integrator = integrator;
  s.time_step = integrator == Integrator::Forward ? 0.2 : 1.0;
  s.substeps = integrator == Integrator::Forward ? 2 : 1;
  OpenCLReactionDiffusionOptions options;
  options.imex_solver = ImexSolver::DeviceConjugateGradients;
  options.cg_max_iterations = 64;
  OpenCLReactionDiffusion rd(compute, domain, s, options);
  rd.run(2);
  bool finite = true;
  for (int m = 0; m < morphogens; ++m)
    for (double x : rd.field_values(m)) finite = finite && std::isfinite(x);
  const FieldStatistics stats = rd.field_statistics(0.5, 1);
  check(finite && std::isfinite(stats.mean), label + ": morphogens finite (mean v " + std::to_string(stats.mean) + ")");
  check(rd.damaged_canaries().empty(), label + ": canaries intact");
}

int run(int argc, char** argv) {
  const ComputeContext compute = make_compute_context("");
  std::printf("device: %s\n", compute.device.describe().c_str());
  if (argc > 1 && std::strcmp(argv[1], "--fault-demo") == 0) {
    run_fault_demo(compute);
    return testing::probe_exit_status();
  }
  // 162 vertices: small enough to interpret, not a multiple of any power-of-two group size, so the
  // padded work-items and their guards are exercised.
  const SurfaceDomain domain = testing::make_domain(testing::make_icosphere(2));
  const int n = domain.vertex_count;
  VertexParameters mixed = uniform_rates(n, 0.02, 0.5);
  for (int i = 0; i < n; ++i) mixed[Param::diffuse_rate][static_cast<size_t>(i)] = (i % 5 == 0) ? 0.0 : 0.01 + 0.0001 * i;
  run_pheromone(compute, domain, uniform_rates(n, 0.02, 0.5), Integrator::Forward, 3.0, "forward Euler, sub-steps");
  // The icosphere's rows all fit the ELL width; the prism's two cap centres (16 neighbours) do not,
  // so its forward step runs the overflow kernel too.
  const SurfaceDomain prism = testing::delaunay_domain("shape:octagonal-prism");
  check(to_hybrid(prism.laplacian, prism.vertex_count).overflow_rows() > 0,
        "the prism has rows longer than the ELL width (" + std::to_string(PHYSARUM_ELL_WIDTH) + ")");
  run_pheromone(compute, prism, uniform_rates(prism.vertex_count, 0.02, 0.5), Integrator::Forward, 3.0,
                "forward Euler, rows past the ELL width");
  run_pheromone(compute, domain, uniform_rates(n, 0.02, 0.5), Integrator::Backward, 0.3, "backward Euler, uniform");
  run_pheromone(compute, domain, mixed, Integrator::Backward, 0.3, "backward Euler, varying and zero diffusion");
  run_pheromone(compute, domain, uniform_rates(n, 0.0, 0.5), Integrator::Backward, 0.3, "backward Euler, no diffusion");
  run_reaction_diffusion(compute, domain, Integrator::Forward, "reaction-diffusion, explicit, held vertices");
  run_reaction_diffusion(compute, prism, Integrator::Forward, "reaction-diffusion, explicit, rows past the ELL width");
  run_reaction_diffusion(compute, prism, Integrator::Forward,
                         "reaction-diffusion, explicit, rows past the ELL width, own weights per morphogen", false);
  run_reaction_diffusion(compute, domain, Integrator::Imex, "reaction-diffusion, IMEX by device CG");
  run_reaction_diffusion(compute, prism, Integrator::Forward,
                         "reaction-diffusion, explicit, five morphogens (eight lanes), own weights", false, 5);
  const SurfaceDomain square = testing::make_domain(testing::make_square_grid(8));
  for (int grouping : {1, 4}) {
    const std::string lanes = ", " + std::to_string(grouping) + " agent(s) per work-item";
    run_agents(compute, domain, Integrator::Forward, grouping, "agents on a sphere, forward Euler" + lanes);
    run_agents(compute, square, Integrator::Backward, grouping, "agents on a square, backward Euler" + lanes);
    run_agents_with_controls(compute, square, Integrator::Forward, grouping,
                             "controls on a square, forward Euler" + lanes);
    run_agents_with_controls(compute, domain, Integrator::Backward, grouping,
                             "controls on a sphere, backward Euler" + lanes);
    run_competing_species(compute, square, grouping, "three species on a square" + lanes);
  }
  run_philox(compute);
  return testing::probe_exit_status();
}

}  // namespace
}  // namespace physarum::opencl

int main(int argc, char** argv) {
  try {
    return physarum::opencl::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "physarum_oclgrind_probe: error: %s\n", e.what());
    return 1;
  }
}
