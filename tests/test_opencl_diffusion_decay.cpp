// The OpenCL pheromone field against the serial reference: one forward-Euler step (with and without
// sub-steps) and one backward-Euler solve element by element, mass balance on the device, device
// statistics against the host's, and canary regions after every buffer a kernel writes.
//
// Tolerances: float32 on the device against double on the host. A forward step is a short sum of
// O(1) terms per vertex, so it agrees to 1e-5 of the field's maximum; conjugate gradients stop at a
// relative residual of 1e-6 on a system whose condition number here is ~10-100, so 1e-4 of the
// maximum bounds the solve's error with room for float rounding.
#include "common/base/errors.hpp"
#include "kernels/device_types.h"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/diffusion_decay.hpp"
#include "opencl/hybrid_matrix.hpp"
#include "opencl/runtime/queued_host_task.hpp"
#include "mass_integral.hpp"
#include "pheromone_rates.hpp"
#include "random_vertex_values.hpp"
#include "reference_field.hpp"
#include "delaunay_domain.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>

namespace physarum::opencl {
namespace {

// OpenCLDiffusionDecay keeps the vertex order of the domain it is given; these tests give it the domain
// as it is, so its device order is the domain's and values change type, not order.
DeviceVertexData<double> as_device(const IntrinsicVertexData<double>& v) { return DeviceVertexData<double>(v.values()); }
IntrinsicVertexData<double> as_domain(const DeviceVertexData<double>& v) { return IntrinsicVertexData<double>(v.values()); }


using testing::delaunay_domain;
using testing::random_values;
using testing::uniform_rates;

// The real surface: the built-in sphere, intrinsic Delaunay (non-negative cotan weights).
const SurfaceDomain& sphere_domain() {
  static const SurfaceDomain domain = delaunay_domain("shape:sphere");
  return domain;
}

// Surfaces whose rows overflow the forward step's ELL width (kernels/device_types.h) with non-zero
// weights, and pad it: the octagonal prism's two cap centres have 17 entries, the skinny sphere's two
// poles 97, their other rows 6 or 7 (the sphere's rows are all alike and fit; the square's 9-entry
// rows overflow only with the zero weight of a right triangle's diagonal).
const SurfaceDomain& prism_domain() {
  static const SurfaceDomain domain = delaunay_domain("shape:octagonal-prism");
  return domain;
}
const SurfaceDomain& skinny_sphere_domain() {
  static const SurfaceDomain domain = delaunay_domain("shape:skinny-sphere");
  return domain;
}

const ComputeContext& compute() {
  static const ComputeContext c = make_compute_context("");
  return c;
}

// Rates that differ per vertex, so a kernel that indexes a rate array wrongly (or reads one value
// for all) disagrees with the reference.
VertexParameters varying_rates(int n, double diffuse, double decay, unsigned seed) {
  VertexParameters p;
  p[Param::diffuse_rate] = random_values(n, seed, 0.5 * diffuse, 1.5 * diffuse);
  p[Param::decay_rate] = random_values(n, seed + 1, 0.5 * decay, 1.5 * decay);
  return p;
}

double max_abs(const IntrinsicVertexData<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Largest |a_i - b_i|, with the vertex where it happens (for the failure message).
std::pair<double, size_t> max_difference(const IntrinsicVertexData<double>& a, const IntrinsicVertexData<double>& b) {
  double worst = -1;
  size_t at = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > worst) worst = std::abs(a[i] - b[i]), at = i;
  return {worst, at};
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// One step of both backends from the same random positive field; returns (reference, device).
struct StepPair {
  IntrinsicVertexData<double> reference, device;
  int reference_sub_steps = 0, device_sub_steps = 0;
  ConjugateGradientReport solve;
  std::vector<std::string> damaged;
};

StepPair one_step(const VertexParameters& params, Integrator integrator, double dt_in_stable_steps, int steps = 1,
                  const SurfaceDomain& d = sphere_domain(), const OpenCLDiffusionDecayOptions& options = {}) {
  // The time step is chosen relative to the stability bound so the sub-step count is known.
  testing::ReferenceField probe(d, params, Integrator::Forward, 1.0);
  const double dt = dt_in_stable_steps * probe.stable_time_step();
  testing::ReferenceField reference(d, params, integrator, dt);
  OpenCLDiffusionDecay device(compute(), d, params, integrator, dt, options);
  const IntrinsicVertexData<double> u0 = random_values(d.vertex_count, 11, 0.1, 1.0);
  reference.set_concentration(u0);
  device.set_concentration(as_device(u0));
  for (int s = 0; s < steps; ++s) {
    reference.step();
    device.step();
  }
  return {reference.concentration(), as_domain(device.concentration()), reference.sub_steps(), device.sub_steps(),
          device.last_solve(), device.damaged_canaries()};
}

TEST(OpenCLDiffusionDecay, SphereDomainIsLargeEnoughAndNotAGroupMultiple) {
  // The canary checks need padding work-items: a vertex count that is not a multiple of the group size.
  EXPECT_GT(sphere_domain().vertex_count, 500);
  EXPECT_NE(sphere_domain().vertex_count % 64, 0);
}

TEST(OpenCLDiffusionDecay, ForwardStepEqualsReference) {
  const int n = sphere_domain().vertex_count;
  for (const VertexParameters& params : {uniform_rates(n, 0.01, 0.5), varying_rates(n, 0.01, 0.5, 3)}) {
    const StepPair r = one_step(params, Integrator::Forward, 0.7);
    ASSERT_EQ(r.reference_sub_steps, 1);
    ASSERT_EQ(r.device_sub_steps, 1);
    const auto [diff, at] = max_difference(r.device, r.reference);
    EXPECT_LE(diff, 1e-5 * max_abs(r.reference)) << "at vertex " << at;
    // The step did something measurable, far above the tolerance: the comparison is not vacuous.
    EXPECT_GT(max_difference(r.reference, random_values(n, 11, 0.1, 1.0)).first, 1e-2);
    EXPECT_TRUE(r.damaged.empty()) << "canaries overwritten in: " << joined(r.damaged);
  }
}

TEST(OpenCLDiffusionDecay, ForwardStepWithSubStepsEqualsReference) {
  const int n = sphere_domain().vertex_count;
  for (const VertexParameters& params : {uniform_rates(n, 0.01, 0.5), varying_rates(n, 0.01, 0.5, 5)}) {
    // 4.5 stable steps: 5 sub-steps, an odd count, so the ping-pong ends in the scratch buffer.
    const StepPair r = one_step(params, Integrator::Forward, 4.5);
    EXPECT_EQ(r.reference_sub_steps, 5);
    EXPECT_EQ(r.device_sub_steps, r.reference_sub_steps);
    const auto [diff, at] = max_difference(r.device, r.reference);
    EXPECT_LE(diff, 1e-5 * max_abs(r.reference)) << "at vertex " << at;
    EXPECT_TRUE(r.damaged.empty()) << "canaries overwritten in: " << joined(r.damaged);
  }
  // An even count ends in u without the copy.
  const StepPair even = one_step(uniform_rates(n, 0.01, 0.5), Integrator::Forward, 3.5, 3);
  EXPECT_EQ(even.device_sub_steps, 4);
  EXPECT_LE(max_difference(even.device, even.reference).first, 1e-5 * max_abs(even.reference));
}

TEST(OpenCLDiffusionDecay, ForwardStepWithPaddedAndOverflowingRowsEqualsReference) {
  for (const SurfaceDomain* d : {&prism_domain(), &skinny_sphere_domain()}) {
    const HybridMatrix hybrid = to_hybrid(d->laplacian, d->vertex_count);
    double overflow_weight = 0.0;
    for (const float w : hybrid.overflow_value) overflow_weight += std::abs(w);
    ASSERT_GT(overflow_weight, 0.0) << "the surface should have rows longer than the ELL width";
    int short_rows = 0;
    for (int i = 0; i < d->vertex_count; ++i)
      short_rows += d->laplacian.row_start[i + 1] - d->laplacian.row_start[i] < PHYSARUM_ELL_WIDTH;
    ASSERT_GT(short_rows, 0) << "the surface should have padded rows";
    const StepPair r = one_step(varying_rates(d->vertex_count, 0.01, 0.5, 7), Integrator::Forward, 2.5, 1, *d);
    EXPECT_EQ(r.device_sub_steps, 3);
    const auto [diff, at] = max_difference(r.device, r.reference);
    EXPECT_LE(diff, 1e-5 * max_abs(r.reference)) << d->vertex_count << " vertices: at vertex " << at;
    EXPECT_TRUE(r.damaged.empty()) << "canaries overwritten in: " << joined(r.damaged);
  }
}

TEST(OpenCLDiffusionDecay, BackwardSolveEqualsReference) {
  const int n = sphere_domain().vertex_count;
  VertexParameters mixed = varying_rates(n, 0.01, 0.5, 9);
  // Some vertices that do not diffuse at all: their rows leave the CG system (common/model/pheromone_operators.hpp).
  for (int i = 0; i < n; i += 7) mixed[Param::diffuse_rate][static_cast<size_t>(i)] = 0.0;
  struct Case {
    const char* name;
    VertexParameters params;
  };
  const Case cases[] = {{"uniform", uniform_rates(n, 0.01, 0.5)},
                        {"varying (row-scaled)", varying_rates(n, 0.01, 0.5, 7)},
                        {"some zero diffusion", mixed}};
  OpenCLDiffusionDecayOptions cg, host;
  cg.implicit_solver = ImplicitSolver::DeviceConjugateGradients;
  host.implicit_solver = ImplicitSolver::HostCholesky;
  for (const Case& c : cases) {
    // 50 stable steps: far beyond forward Euler's limit, so the implicit solve does real work.
    const StepPair r = one_step(c.params, Integrator::Backward, 50.0, 1, sphere_domain(), cg);
    const auto [diff, at] = max_difference(r.device, r.reference);
    EXPECT_LE(diff, 1e-4 * max_abs(r.reference)) << c.name << ": at vertex " << at;
    EXPECT_TRUE(r.solve.converged) << c.name << ": " << r.solve.iterations << " iterations, residual "
                                   << r.solve.relative_residual;
    EXPECT_GT(r.solve.iterations, 1) << c.name;
    EXPECT_LE(r.solve.relative_residual, 1e-6) << c.name;
    EXPECT_TRUE(r.damaged.empty()) << c.name << ": canaries overwritten in: " << joined(r.damaged);
    // The host's float Cholesky factor (what a CPU device uses): as close as the CG's tolerance.
    const StepPair h = one_step(c.params, Integrator::Backward, 50.0, 1, sphere_domain(), host);
    const auto [host_diff, host_at] = max_difference(h.device, h.reference);
    EXPECT_LE(host_diff, 1e-5 * max_abs(h.reference)) << c.name << ": host solve, at vertex " << host_at;
    EXPECT_EQ(h.solve.iterations, 0) << c.name;
    EXPECT_TRUE(h.damaged.empty()) << c.name << ": canaries overwritten in: " << joined(h.damaged);
  }
}

// PoCL is a CPU device: Automatic solves there with the host factor; asked for, CG runs anyway. A GPU
// solves only small systems on the host (DeviceTuning::host_implicit_solve_max_vertices).
TEST(OpenCLDiffusionDecay, AutomaticSolverIsTheHostFactorOnACpuDevice) {
  const SurfaceDomain& d = sphere_domain();
  const VertexParameters params = uniform_rates(d.vertex_count, 0.01, 0.5);
  OpenCLDiffusionDecay automatic(compute(), d, params, Integrator::Backward, 1.0);
  EXPECT_EQ(automatic.solves_on_host(), compute().device.type == "CPU" ||
                                            d.vertex_count <= tuning_for(compute().device).host_implicit_solve_max_vertices);
  if (compute().device.type == "CPU") {
    EXPECT_TRUE(implicit_solve_on_host(compute().device, 1 << 30));
  }
  OpenCLDiffusionDecayOptions cg;
  cg.implicit_solver = ImplicitSolver::DeviceConjugateGradients;
  EXPECT_FALSE(OpenCLDiffusionDecay(compute(), d, params, Integrator::Backward, 1.0, cg).solves_on_host());
}

// The host factor in the device's queue (a native kernel, opencl/runtime/queued_host_task.hpp) and on the
// field mapped by the host run the same arithmetic on the same floats: bit for bit the same field,
// over steps with the kernels the queue runs around the solve (the write rate's source before it and
// its clamp after) and blocking deposits between steps. A queued solve that read the field before the
// source kernel, or that the clamp kernel overtook, would differ.
TEST(OpenCLDiffusionDecay, HostSolveInTheQueueEqualsTheMappedSolveBitForBit) {
  const SurfaceDomain& d = sphere_domain();
  const int n = d.vertex_count;
  const VertexParameters params = varying_rates(n, 0.01, 0.5, 29);
  testing::ReferenceField probe(d, params, Integrator::Forward, 1.0);
  const double dt = 50.0 * probe.stable_time_step();
  // Sources everywhere (up to 1 per step), and at every 40th vertex a sink strong enough that the
  // clamp at zero acts around it (about a quarter of the vertices end at zero).
  IntrinsicVertexData<double> rate = random_values(n, 31, 0.0, 1.0 / dt);
  for (int i = 0; i < n; i += 40) rate[static_cast<size_t>(i)] = -20.0 / dt;
  const IntrinsicVertexData<double> u0 = random_values(n, 37, 0.1, 1.0);
  const IntrinsicVertexData<double> amount = random_values(n, 41, 0.0, 1e-3);
  OpenCLDiffusionDecayOptions queued, mapped;
  queued.implicit_solver = mapped.implicit_solver = ImplicitSolver::HostCholesky;
  mapped.host_solve_in_queue = false;
  OpenCLDiffusionDecay a(compute(), d, params, Integrator::Backward, dt, queued);
  OpenCLDiffusionDecay b(compute(), d, params, Integrator::Backward, dt, mapped);
  EXPECT_EQ(a.solves_in_queue(), runs_queued_host_tasks(compute().device));
  EXPECT_FALSE(b.solves_in_queue());
  for (OpenCLDiffusionDecay* f : {&a, &b}) {
    f->set_write_rate(as_device(rate));
    f->set_concentration(as_device(u0));
    for (int s = 0; s < 5; ++s) {
      f->step();
      if (s == 2) f->add_deposits(as_device(amount));
    }
  }
  const IntrinsicVertexData<double> ua = as_domain(a.concentration()), ub = as_domain(b.concentration());
  int clamped = 0;
  for (int i = 0; i < n; ++i) {
    const size_t k = static_cast<size_t>(i);
    ASSERT_EQ(ua[k], ub[k]) << "vertex " << i;
    if (ua[k] == 0.0) ++clamped;
  }
  // The steps did real work: some vertices clamped, most not (a field driven to zero everywhere would
  // agree whatever the solve did), and the field moved from where it started.
  EXPECT_GT(clamped, 0);
  EXPECT_LT(clamped, n / 2);
  EXPECT_GT(max_difference(ua, u0).first, 0.1);
  EXPECT_TRUE(a.damaged_canaries().empty()) << joined(a.damaged_canaries());
}

TEST(OpenCLDiffusionDecay, BackwardWithoutDiffusionIsTheExactDecayFactor) {
  const SurfaceDomain& d = sphere_domain();
  const VertexParameters params = uniform_rates(d.vertex_count, 0.0, 0.5);
  OpenCLDiffusionDecay device(compute(), d, params, Integrator::Backward, 0.2);
  const IntrinsicVertexData<double> u0 = random_values(d.vertex_count, 13, 0.1, 1.0);
  device.set_concentration(as_device(u0));
  device.step();
  const IntrinsicVertexData<double> u1 = as_domain(device.concentration());
  for (size_t i = 0; i < u0.size(); ++i) ASSERT_NEAR(u1[i], u0[i] / (1.0 + 0.2 * 0.5), 1e-6) << "vertex " << i;
  EXPECT_TRUE(device.damaged_canaries().empty()) << joined(device.damaged_canaries());
}

TEST(OpenCLDiffusionDecay, DiffusionAloneConservesTheTotalAmount) {
  const SurfaceDomain& d = sphere_domain();
  // A uniform diffuse rate: 1^T L = 0 makes sum m u invariant (a varying R_dif does not conserve it:
  // 1^T R_dif L != 0). The sphere's vertex masses differ, so a scheme that forgot M^-1 would drift.
  const VertexParameters params = uniform_rates(d.vertex_count, 0.01, 0.0);
  testing::ReferenceField probe(d, params, Integrator::Forward, 1.0);
  for (Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    OpenCLDiffusionDecay device(compute(), d, params, integrator, 3.0 * probe.stable_time_step());
    const IntrinsicVertexData<double> u0 = random_values(d.vertex_count, 17, 0.0, 1.0);
    device.set_concentration(as_device(u0));
    const double before = device.total_amount();
    double host_before = 0;
    for (int i = 0; i < d.vertex_count; ++i) host_before += d.vertex_mass[i] * static_cast<float>(u0[i]);
    EXPECT_NEAR(before / host_before, 1.0, 1e-6) << "device sum of m u";
    for (int s = 0; s < 20; ++s) device.step();
    const IntrinsicVertexData<double> u = as_domain(device.concentration());
    EXPECT_NEAR(testing::mass_integral(d, u) / host_before, 1.0, 2e-5);
    EXPECT_NEAR(device.total_amount() / host_before, 1.0, 2e-5);
    // ... and it did diffuse: the spread of the random start shrank a lot.
    const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
    EXPECT_LT(*hi - *lo, 0.6);
  }
}

TEST(OpenCLDiffusionDecay, DecayAloneScalesByOneMinusRateTimesStep) {
  const SurfaceDomain& d = sphere_domain();
  const double rate = 0.5, dt = 0.1;
  OpenCLDiffusionDecay device(compute(), d, uniform_rates(d.vertex_count, 0.0, rate), Integrator::Forward, dt);
  ASSERT_EQ(device.sub_steps(), 1);
  const IntrinsicVertexData<double> u0 = random_values(d.vertex_count, 19, 0.1, 1.0);
  device.set_concentration(as_device(u0));
  const double before = device.total_amount();
  device.step();
  const IntrinsicVertexData<double> u1 = as_domain(device.concentration());
  for (size_t i = 0; i < u0.size(); ++i)
    ASSERT_NEAR(u1[i], (1.0 - rate * dt) * u0[i], 2e-7) << "vertex " << i;
  for (int s = 1; s < 10; ++s) device.step();
  EXPECT_NEAR(device.total_amount() / before, std::pow(1.0 - rate * dt, 10), 1e-5);
}

TEST(OpenCLDiffusionDecay, DepositsRaiseConcentrationByAmountOverMass) {
  const SurfaceDomain& d = sphere_domain();
  OpenCLDiffusionDecay device(compute(), d, uniform_rates(d.vertex_count, 0.01, 0.5), Integrator::Forward, 0.01);
  device.fill(0.25);
  const IntrinsicVertexData<double> amount = random_values(d.vertex_count, 23, 0.0, 1e-3);
  device.add_deposits(as_device(amount));
  const IntrinsicVertexData<double> u = as_domain(device.concentration());
  for (size_t i = 0; i < u.size(); ++i)
    ASSERT_NEAR(u[i], 0.25 + amount[i] / d.vertex_mass[i], 1e-5 * (0.25 + amount[i] / d.vertex_mass[i])) << i;
  EXPECT_TRUE(device.damaged_canaries().empty()) << joined(device.damaged_canaries());
}

TEST(OpenCLFieldStatistics, EqualTheHostsOnTheReadBackField) {
  const SurfaceDomain& d = sphere_domain();
  OpenCLDiffusionDecay device(compute(), d, uniform_rates(d.vertex_count, 0.01, 0.5), Integrator::Forward, 0.01);
  device.set_concentration(as_device(random_values(d.vertex_count, 29, 0.0, 1.0)));
  device.step();  // a field the device made, not just the one uploaded
  const IntrinsicVertexData<double> u = as_domain(device.concentration());
  // U = 0.4 puts the thresholds 0.2, 0.4 and 0.8 inside the field's range: coverages away from 0 and 1.
  const double U = 0.4;
  const FieldStatistics host = compute_field_statistics(u, d.vertex_mass, U);
  const FieldStatistics dev = device.statistics(U);
  EXPECT_NEAR(dev.mean, host.mean, 1e-5 * host.mean);
  EXPECT_EQ(dev.U, U);
  for (size_t k = 0; k < host.coverage.size(); ++k) {
    EXPECT_GT(host.coverage[k], 0.05);
    EXPECT_LT(host.coverage[k], 0.95);
    EXPECT_NEAR(dev.coverage[k], host.coverage[k], 1e-6) << "coverage at " << kCoverageMultiples[k] << " U";
  }
  EXPECT_NEAR(device.total_amount(), host.mean * d.total_area, 1e-5 * host.mean * d.total_area);
  // A constant field above every threshold covers everything, exactly (same sums for both sides of the ratio).
  device.fill(10.0);
  const FieldStatistics full = device.statistics(U);
  for (double c : full.coverage) EXPECT_EQ(c, 1.0);
  EXPECT_NEAR(full.mean, 10.0, 1e-5);
  EXPECT_TRUE(device.damaged_canaries().empty()) << joined(device.damaged_canaries());
}

TEST(OpenCLDiffusionDecay, RejectsBadInputAndOversizedBuffers) {
  const SurfaceDomain& d = sphere_domain();
  EXPECT_THROW(OpenCLDiffusionDecay(compute(), d, uniform_rates(d.vertex_count - 1, 0.01, 0.5), Integrator::Forward, 0.1),
               InputError);
  EXPECT_THROW(OpenCLDiffusionDecay(compute(), d, uniform_rates(d.vertex_count, 0.01, 0.5), Integrator::Forward, 0.0),
               InputError);
  OpenCLDiffusionDecay ok(compute(), d, uniform_rates(d.vertex_count, 0.01, 0.5), Integrator::Forward, 0.1);
  EXPECT_THROW(ok.set_concentration(DeviceVertexData<double>(3, 1.0)), InputError);
  // A device whose largest allocation is smaller than the sub-step matrix: a clear error, not a crash.
  ComputeContext small = compute();
  small.device.max_allocation_bytes = 1024;
  try {
    OpenCLDiffusionDecay tiny(small, d, uniform_rates(d.vertex_count, 0.01, 0.5), Integrator::Forward, 0.1);
    FAIL() << "expected DeviceError";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("forward Euler"), std::string::npos) << m;
    EXPECT_NE(m.find("1024"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace physarum::opencl
