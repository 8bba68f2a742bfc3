// Reaction-diffusion on the OpenCL backend (opencl/reaction_diffusion.hpp): Gray-Scott, two
// morphogens, on flat square grids of 32^2 .. 1000^2 cells (10^3 .. 10^6 vertices; every interior
// vertex has six neighbours, as on a regular triangle mesh, so every row fits the ELL width and
// the grid's row-by-row numbering is already local).
//
//   BM_RdExplicitStep   one explicit sub-step; counters: vertices, bytes the step must move
//                       (OpenCLReactionDiffusion::bytes_per_sub_step) per second, and that as a
//                       fraction of the device's measured STREAM-triad bandwidth (opencl/runtime/memory_bandwidth):
//                       the step is bandwidth-bound, so this is its roofline fraction.
//   BM_RdExplicitStepReference  the same step on the reference backend.
//   BM_RdExplicitStepFiveMorphogens(Reference)  the same with five morphogens (the float8 path).
//   BM_RdImexStep       one IMEX step (dt = 10x the explicit stability bound) with the device's
//                       conjugate gradients (warm-started) or the host factorization, against
//   BM_RdImexHostOnly   the same step done entirely on the host in double (right-hand side and
//                       SimplicialLDLT solves), what a host reference backend pays.
#include "bench/bench_backends.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "opencl/runtime/memory_bandwidth.hpp"
#include "opencl/reaction_diffusion.hpp"
#include "reference/reaction_diffusion.hpp"
#include "tests/rough_gray_scott.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace physarum::bench {
namespace {

// Gray-Scott from a rough state on square grids (tests/rough_gray_scott.hpp).
using testing::grid_domain;
using testing::rough_gray_scott;
using testing::stable_step;

// The device's triad bandwidth now: measured right beside each timing, because the machine is
// shared and its bandwidth moves with the load (a bound measured minutes apart is not a bound).
double triad_bandwidth() {
  static opencl::DeviceTriad triad(compute());
  return triad.bytes_per_second(3);
}

// Times explicit steps of `s` on the device, with the counters: vertices, bytes the step must move
// per second and that as a fraction of the triad bandwidth measured right after.
void time_explicit_steps(benchmark::State& state, const SurfaceDomain& domain, const ReactionDiffusionSystem& s) {
  opencl::OpenCLReactionDiffusion rd(compute(), domain, s);
  rd.run(2);
  rd.finish();
  for (auto _ : state) {
    rd.step();
    rd.finish();
  }
  const double bytes = rd.bytes_per_sub_step();
  const double bandwidth = triad_bandwidth();  // right after the timing (see triad_bandwidth)
  state.counters["vertices"] = domain.vertex_count;
  state.counters["bytes_per_step"] = bytes;
  state.counters["bytes_per_s"] =
      benchmark::Counter(bytes * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["triad_bytes_per_s"] = bandwidth;
  state.SetLabel(compute().device.type);
  // bytes_per_s / triad_bytes_per_s: the roofline fraction (a rate counter divides by the time).
  state.counters["bound_fraction"] = benchmark::Counter(bytes * static_cast<double>(state.iterations()) / bandwidth,
                                                        benchmark::Counter::kIsRate);
}

void BM_RdExplicitStep(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(0)));
  ReactionDiffusionSystem s = rough_gray_scott(domain, Integrator::Forward, 0.5 * stable_step(domain, 2e-5));
  if (state.range(1) != 0) {
    // Weights that are not multiples of u's, as anisotropic diffusion makes them: each coupling of
    // v scaled by a factor in [0.4, 1] symmetric in its two vertices, the diagonal reset so rows
    // still sum to zero (a diffusion operator). v then reads its own block of weights, 4 more
    // bytes a slot; weaker couplings stay stable at the same step.
    CsrMatrix& K = s.stiffness[1];
    for (int i = 0; i < K.rows; ++i) {
      double off_diagonal = 0.0;
      int diagonal = -1;
      for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e) {
        const int j = K.column[e];
        if (j == i) {
          diagonal = e;
          continue;
        }
        K.value[e] *= 0.7 + 0.3 * std::sin(0.37 * std::min(i, j) + 0.11 * std::max(i, j));
        off_diagonal += K.value[e];
      }
      if (diagonal >= 0) K.value[diagonal] = -off_diagonal;
    }
  }
  time_explicit_steps(state, domain, s);
}
// Args: {cells per side, own weights per morphogen (0: shared, the isotropic case)}.
BENCHMARK(BM_RdExplicitStep)
    ->ArgsProduct({{100, 316, 1000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Gray-Scott plus linear morphogens up to `count` (w' = 0.5 u - w, then each 0.2 x the one before
// minus 0.4 x itself), each diffusing at its own fraction of u's rate: five morphogens, the size of
// Meinhardt's stripe system (004, appendix 8.3), take the kernel's eight-lane path.
ReactionDiffusionSystem with_linear_morphogens(ReactionDiffusionSystem s, int count) {
  const std::vector<std::string> names = {"w", "s", "t", "p", "q", "r"};
  for (int m = 2; m < count; ++m) {
    const std::string& name = names[static_cast<size_t>(m - 2)];
    s.reaction.push_back(m == 2 ? "0.5*u - w" : "0.2*" + names[static_cast<size_t>(m - 3)] + " - 0.4*" + name);
    s.morphogens.push_back(name);
    CsrMatrix K = s.stiffness[0];
    for (double& v : K.value) v *= 0.4 + 0.1 * m;
    s.stiffness.push_back(std::move(K));
    IntrinsicVertexData<double> initial = s.initial[0];
    for (double& v : initial) v *= 0.5;
    s.initial.push_back(std::move(initial));
    if (!s.minimum.empty()) s.minimum.push_back(-std::numeric_limits<double>::infinity());
  }
  return s;
}

// One explicit sub-step of five morphogens (shared weights), with BM_RdExplicitStep's counters.
void BM_RdExplicitStepFiveMorphogens(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(0)));
  const ReactionDiffusionSystem s =
      with_linear_morphogens(rough_gray_scott(domain, Integrator::Forward, 0.5 * stable_step(domain, 2e-5)), 5);
  time_explicit_steps(state, domain, s);
}
BENCHMARK(BM_RdExplicitStepFiveMorphogens)->Arg(100)->Arg(316)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RdExplicitStepFiveMorphogensReference(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(0)));
  ReferenceReactionDiffusion rd(
      with_linear_morphogens(rough_gray_scott(domain, Integrator::Forward, 0.5 * stable_step(domain, 2e-5)), 5));
  rd.step();
  for (auto _ : state) rd.step();
  state.SetLabel("reference");
  state.counters["vertices"] = domain.vertex_count;
}
BENCHMARK(BM_RdExplicitStepFiveMorphogensReference)->Arg(100)->Arg(316)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same explicit step on the reference backend (reference/reaction_diffusion.hpp: double, the
// kinetics through the formula evaluator): the denominator of the OpenCL >= 5x target.
void BM_RdExplicitStepReference(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(0)));
  ReferenceReactionDiffusion rd(rough_gray_scott(domain, Integrator::Forward, 0.5 * stable_step(domain, 2e-5)));
  rd.step();
  for (auto _ : state) rd.step();
  state.SetLabel("reference");
  state.counters["vertices"] = domain.vertex_count;
}
BENCHMARK(BM_RdExplicitStepReference)->Arg(100)->Arg(316)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RdImexStep(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(1)));
  const ReactionDiffusionSystem s = rough_gray_scott(domain, Integrator::Imex, 10 * stable_step(domain, 2e-5));
  opencl::OpenCLReactionDiffusionOptions options;
  options.imex_solver =
      state.range(0) == 0 ? opencl::ImexSolver::DeviceConjugateGradients : opencl::ImexSolver::HostFactorization;
  // Each timed step starts from the rough state again (set_field is not timed), so every step
  // solves from the same distance: the warm start is the previous values, as in a run.
  opencl::OpenCLReactionDiffusion rd(compute(), domain, s, options);
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    rd.set_field(s.initial[0], 0);
    rd.set_field(s.initial[1], 1);
    rd.finish();
    state.ResumeTiming();
    rd.step();
    rd.finish();
    iterations = rd.last_solve().iterations;
  }
  state.SetLabel(state.range(0) == 0 ? "device CG" : "host factorization");
  state.counters["vertices"] = domain.vertex_count;
  if (state.range(0) == 0) state.counters["cg_iterations"] = iterations;
}
BENCHMARK(BM_RdImexStep)
    ->ArgsProduct({{0, 1}, {31, 100, 316, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_RdImexHostOnly(benchmark::State& state) {
  const SurfaceDomain& domain = grid_domain(static_cast<int>(state.range(0)));
  const ReactionDiffusionSystem s = rough_gray_scott(domain, Integrator::Imex, 10 * stable_step(domain, 2e-5));
  const int n = domain.vertex_count;
  const double h = s.time_step;
  std::vector<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> factors(2);
  for (int m = 0; m < 2; ++m) {
    Eigen::SparseMatrix<double> A = s.stiffness[static_cast<size_t>(m)].to_eigen() * h;
    for (int i = 0; i < n; ++i) A.coeffRef(i, i) += s.mass[i];
    factors[static_cast<size_t>(m)].compute(A);
  }
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(s.initial[0].data(), n);
  Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(s.initial[1].data(), n);
  Eigen::VectorXd bu(n), bv(n);
  for (auto _ : state) {
    for (int i = 0; i < n; ++i) {
      const double uvv = u[i] * v[i] * v[i];
      bu[i] = s.mass[i] * (u[i] + h * (-uvv + 0.04 * (1 - u[i])));
      bv[i] = s.mass[i] * (v[i] + h * (uvv - 0.1 * v[i]));
    }
    u = factors[0].solve(bu);
    v = factors[1].solve(bv);
    benchmark::DoNotOptimize(u.data());
  }
  state.SetLabel("host only, double");
  state.counters["vertices"] = n;
}
BENCHMARK(BM_RdImexHostOnly)->Arg(31)->Arg(100)->Arg(316)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace physarum::bench
