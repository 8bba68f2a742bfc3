// Reaction-diffusion on the OpenCL device (opencl/reaction_diffusion.hpp) against plain
// double-precision loops written here, from the equations of common/reaction_diffusion/reaction_diffusion_system.hpp:
//   explicit sub-step  u_m += h (-(K_m u_m)_i / m_i + R_m(u)_i)
//   IMEX step          (M + h K_m) u_m' = M (u_m + h R_m(u)), solved by Eigen's SimplicialLDLT
// with Gray-Scott kinetics (Pearson 1993), K_m = D_m L on shape:sphere, shape:square and the
// octagonal prism (whose cap centres have rows longer than the device's ELL width), random states.
//
// Tolerances. Explicit: the device computes in float32; one sub-step is a sum of about eight
// products plus the kinetics, so its rounding is a few float ulps (~1e-7 relative each) of the
// largest value involved, and three sub-steps stay well below 2e-6 of it; 1e-5 of max(1, the
// largest |value|) leaves room and is still 100x smaller than the step's change (checked below), so
// a wrong term cannot hide in it. (On the prism, whose cap centres are very unlike their
// neighbours, the state reaches |u| ~ 24 in three sub-steps, in the double loop as on the device.)
// IMEX: the right-hand side is float32 and the device CG stops at a relative residual of 1e-6 on a
// system M + h K whose condition number is ~1 + h D lambda_max / m ~ 10 here: 1e-5 absolute on O(1)
// values; the host factorization solves in double from the float right-hand side: the same bound.
#include "common/base/errors.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/simulation/simulation_state.hpp"
#include "delaunay_domain.hpp"
#include "opencl/reaction_diffusion.hpp"
#include "random_vertex_values.hpp"
#include "rough_gray_scott.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <cmath>
#include <functional>

namespace physarum::opencl {
namespace {

const ComputeContext& compute() {
  static const ComputeContext c = make_compute_context("");
  return c;
}

const SurfaceDomain& domain_of(const std::string& spec) {
  static std::map<std::string, SurfaceDomain> domains;
  auto found = domains.find(spec);
  if (found == domains.end()) found = domains.emplace(spec, testing::delaunay_domain(spec)).first;
  return found->second;
}

using testing::random_values;

CsrMatrix scaled(const CsrMatrix& L, double factor) {
  CsrMatrix K = L;
  for (double& v : K.value) v *= factor;
  return K;
}

// Gray-Scott on `domain`: D_u = 2 D_v, F varying per vertex (a map: the per-vertex buffer path), k
// uniform (the compile-time literal path), random u in [0.3, 1], v in [0, 0.5].
ReactionDiffusionSystem gray_scott(const SurfaceDomain& domain, double D_v, Integrator integrator, double dt,
                                   int substeps) {
  const int n = domain.vertex_count;
  ReactionDiffusionSystem s;
  s.morphogens = {"u", "v"};
  s.reaction = {"-u*v^2 + F*(1-u)", "u*v^2 - (F+k)*v"};
  s.coefficient_names = {"F", "k"};
  s.coefficients = {random_values(n, 11, 0.03, 0.05), IntrinsicVertexData<double>(static_cast<size_t>(n), 0.06)};
  s.stiffness = {scaled(domain.laplacian, 2.0 * D_v), scaled(domain.laplacian, D_v)};
  s.mass = domain.vertex_mass;
  s.initial = {random_values(n, 12, 0.3, 1.0), random_values(n, 13, 0.0, 0.5)};
  s.integrator = integrator;
  s.time_step = dt;
  s.substeps = substeps;
  return s;
}

// The Gray-Scott kinetics in double, written out (not parsed): R_u, R_v.
std::array<double, 2> gray_scott_reaction(double u, double v, double F, double k) {
  return {-u * v * v + F * (1.0 - u), u * v * v - (F + k) * v};
}

// The largest explicit step for which a forward Euler sub-step of the fastest diffusion is stable,
// roughly (Gershgorin): tests/rough_gray_scott.hpp.
using testing::stable_step;

// Every morphogen's reaction at vertex i of state u, written out in double.
using Kinetics = std::function<std::vector<double>(const std::vector<IntrinsicVertexData<double>>& u, size_t i)>;

// The state after one step of the system, in double: the explicit integrator's sub-steps, with
// `kinetics` (Gray-Scott's when none is given).
std::vector<IntrinsicVertexData<double>> explicit_reference(const ReactionDiffusionSystem& s, Kinetics kinetics = {}) {
  if (!kinetics)
    kinetics = [&s](const std::vector<IntrinsicVertexData<double>>& u, size_t i) {
      const auto r = gray_scott_reaction(u[0][i], u[1][i], s.coefficients[0][i], s.coefficients[1][i]);
      return std::vector<double>(r.begin(), r.end());
    };
  std::vector<IntrinsicVertexData<double>> u = s.initial;
  const size_t n = s.mass.size();
  const double h = s.time_step / s.substeps;
  for (int step = 0; step < s.substeps; ++step) {
    std::vector<IntrinsicVertexData<double>> next = u;
    for (size_t i = 0; i < n; ++i) {
      if (!s.fixed.empty() && s.fixed[i]) continue;
      const std::vector<double> r = kinetics(u, i);
      for (int m = 0; m < static_cast<int>(u.size()); ++m) {
        const CsrMatrix& K = s.stiffness[static_cast<size_t>(m)];
        double Ku = 0.0;
        for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e) Ku += K.value[e] * u[m][K.column[e]];
        next[m][i] = u[m][i] + h * (-Ku / s.mass[i] + r[static_cast<size_t>(m)]);
      }
    }
    u = next;
  }
  return u;
}

// One IMEX step in double: for each morphogen, the free vertices solve
// (M + h K)_ff x_f = M_f (u_f + h R_f) - h K_fd u_d (held values u_d known) by SimplicialLDLT.
std::vector<IntrinsicVertexData<double>> imex_reference(const ReactionDiffusionSystem& s) {
  const int n = static_cast<int>(s.mass.size());
  const double h = s.time_step;
  std::vector<int> free_index(static_cast<size_t>(n), -1);
  int free_count = 0;
  for (int i = 0; i < n; ++i)
    if (s.fixed.empty() || !s.fixed[i]) free_index[static_cast<size_t>(i)] = free_count++;
  std::vector<IntrinsicVertexData<double>> out = s.initial;
  for (int m = 0; m < 2; ++m) {
    const CsrMatrix& K = s.stiffness[static_cast<size_t>(m)];
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd b(free_count);
    for (int i = 0; i < n; ++i) {
      const int fi = free_index[static_cast<size_t>(i)];
      if (fi < 0) continue;
      const auto r = gray_scott_reaction(s.initial[0][i], s.initial[1][i], s.coefficients[0][i], s.coefficients[1][i]);
      b[fi] = s.mass[i] * (s.initial[m][i] + h * r[static_cast<size_t>(m)]);
      entries.emplace_back(fi, fi, s.mass[i]);
      for (int e = K.row_start[i]; e < K.row_start[i + 1]; ++e) {
        const int j = K.column[e];
        const int fj = free_index[static_cast<size_t>(j)];
        if (fj >= 0) entries.emplace_back(fi, fj, h * K.value[e]);
        else b[fi] -= h * K.value[e] * s.initial[m][j];
      }
    }
    Eigen::SparseMatrix<double> A(free_count, free_count);
    A.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    EXPECT_EQ(solver.info(), Eigen::Success);
    const Eigen::VectorXd x = solver.solve(b);
    for (int i = 0; i < n; ++i)
      if (free_index[static_cast<size_t>(i)] >= 0) out[m][i] = x[free_index[static_cast<size_t>(i)]];
  }
  return out;
}

double largest_magnitude(const IntrinsicVertexData<double>& a) {
  double largest = 0.0;
  for (double x : a) largest = std::max(largest, std::abs(x));
  return largest;
}

double max_difference(const IntrinsicVertexData<double>& a, const IntrinsicVertexData<double>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

std::vector<IntrinsicVertexData<double>> one_step(const SurfaceDomain& domain, const ReactionDiffusionSystem& s,
                                                  const OpenCLReactionDiffusionOptions& options = {}) {
  OpenCLReactionDiffusion rd(compute(), domain, s, options);
  rd.step();
  EXPECT_EQ(rd.damaged_canaries(), std::vector<std::string>{});
  EXPECT_DOUBLE_EQ(rd.time(), s.time_step);
  return {rd.field_values(0), rd.field_values(1)};
}

constexpr double kExplicitTolerance = 1e-5;
constexpr double kImexTolerance = 1e-5;

std::string ShapeName(const ::testing::TestParamInfo<std::string>& p) {
  return p.param == "shape:octagonal-prism" ? std::string("prism") : p.param.substr(6);
}
std::string SolverName(const ::testing::TestParamInfo<ImexSolver>& p) {
  return p.param == ImexSolver::HostFactorization ? "HostFactorization" : "DeviceCG";
}

class ExplicitStep : public ::testing::TestWithParam<std::string> {};

void expect_explicit_step_matches(const SurfaceDomain& domain, const ReactionDiffusionSystem& s) {
  const auto device = one_step(domain, s);
  const auto reference = explicit_reference(s);
  for (int m = 0; m < 2; ++m) {
    size_t worst = 0;
    for (size_t i = 0; i < device[m].size(); ++i)
      if (std::abs(device[m][i] - reference[m][i]) > std::abs(device[m][worst] - reference[m][worst])) worst = i;
    EXPECT_LT(max_difference(device[m], reference[m]), kExplicitTolerance * std::max(1.0, largest_magnitude(reference[m])))
        << "morphogen " << m << " vertex " << worst << " (row of "
        << domain.laplacian.row_start[worst + 1] - domain.laplacian.row_start[worst] << " entries; value "
        << reference[m][worst] << ")";
    // The step moves the state far more than the tolerance, so a missing term would show.
    EXPECT_GT(max_difference(reference[m], s.initial[m]), 100 * kExplicitTolerance) << "morphogen " << m;
  }
}

// Three sub-steps each at 0.8 of the fastest morphogen's (2 D_v) stability bound. The stiffness
// matrices are proportional (2 D_v L and D_v L): the device's shared-weights path.
TEST_P(ExplicitStep, MatchesTheDoubleLoopElementWise) {
  const SurfaceDomain& domain = domain_of(GetParam());
  const double D_v = 1e-3;
  const double h = 0.8 * stable_step(domain, 2.0 * D_v);
  expect_explicit_step_matches(domain, gray_scott(domain, D_v, Integrator::Forward, 3 * h, 3));
}

// Stiffness matrices that are not multiples of one another (as anisotropic diffusion makes them):
// each morphogen's own weights, ELL and overflow rows (the prism's cap centres).
TEST_P(ExplicitStep, MatchesTheDoubleLoopWithUnrelatedStiffnesses) {
  const SurfaceDomain& domain = domain_of(GetParam());
  const double D_v = 1e-3;
  const double h = 0.8 * stable_step(domain, 2.0 * D_v);
  ReactionDiffusionSystem s = gray_scott(domain, D_v, Integrator::Forward, 3 * h, 3);
  for (size_t e = 0; e < s.stiffness[1].value.size(); ++e) s.stiffness[1].value[e] *= 0.6 + 0.4 * std::sin(double(e));
  expect_explicit_step_matches(domain, s);
}

// Three to eight morphogens (custom kinetics): the device sums every morphogen's diffusion of a slot
// as one short vector (a float3 or float4 for these counts, a float2 for two, a float8 with repeated
// lanes for five to eight), so each vector width is its own code path. Gray-Scott's u and v plus linear kinetics coupling the extra morphogens to them
// (w' = 0.5 u - w, x' = v w - 0.3 x), each diffusing at its own rate (proportional stiffnesses: the
// shared-weights path; and with x's weights perturbed: each morphogen's own weights).
TEST_P(ExplicitStep, MatchesTheDoubleLoopWithThreeToEightMorphogens) {
  const SurfaceDomain& domain = domain_of(GetParam());
  const int n = domain.vertex_count;
  const double D_v = 1e-3;
  const double h = 0.8 * stable_step(domain, 2.0 * D_v);
  // Past x, each further morphogen decays towards a fifth of the one before it (y' = 0.2 x - 0.4 y,
  // ...) and diffuses at a rate of its own.
  const std::vector<std::string> more = {"y", "z", "p", "q"};
  for (const int count : {3, 4, 5, 8})
    for (const bool own_weights : {false, true}) {
      ReactionDiffusionSystem s = gray_scott(domain, D_v, Integrator::Forward, 3 * h, 3);
      s.morphogens.push_back("w");
      s.reaction.push_back("0.5*u - w");
      s.stiffness.push_back(scaled(domain.laplacian, 1.5 * D_v));
      s.initial.push_back(random_values(n, 14, 0.0, 1.0));
      if (count >= 4) {
        s.morphogens.push_back("x");
        s.reaction.push_back("v*w - 0.3*x");
        s.stiffness.push_back(scaled(domain.laplacian, 0.5 * D_v));
        s.initial.push_back(random_values(n, 15, 0.0, 1.0));
      }
      for (int m = 4; m < count; ++m) {
        s.morphogens.push_back(more[static_cast<size_t>(m - 4)]);
        s.reaction.push_back("0.2*" + s.morphogens[static_cast<size_t>(m - 1)] + " - 0.4*" + s.morphogens.back());
        s.stiffness.push_back(scaled(domain.laplacian, (0.3 + 0.2 * m) * D_v));
        s.initial.push_back(random_values(n, 16 + static_cast<unsigned>(m), 0.0, 1.0));
      }
      if (own_weights)
        for (size_t e = 0; e < s.stiffness.back().value.size(); ++e)
          s.stiffness.back().value[e] *= 0.6 + 0.4 * std::sin(double(e));
      const auto u = explicit_reference(s, [&](const std::vector<IntrinsicVertexData<double>>& v, size_t i) {
        const auto gs = gray_scott_reaction(v[0][i], v[1][i], s.coefficients[0][i], s.coefficients[1][i]);
        std::vector<double> r = {gs[0], gs[1], 0.5 * v[0][i] - v[2][i]};
        if (count >= 4) r.push_back(v[1][i] * v[2][i] - 0.3 * v[3][i]);
        for (int m = 4; m < count; ++m) r.push_back(0.2 * v[static_cast<size_t>(m - 1)][i] - 0.4 * v[static_cast<size_t>(m)][i]);
        return r;
      });
      OpenCLReactionDiffusion rd(compute(), domain, s);
      rd.step();
      for (int m = 0; m < count; ++m) {
        const IntrinsicVertexData<double> device = rd.field_values(m);
        EXPECT_LT(max_difference(device, u[m]), kExplicitTolerance * std::max(1.0, largest_magnitude(u[m])))
            << count << " morphogens" << (own_weights ? ", own weights" : "") << ", morphogen " << m;
        EXPECT_GT(max_difference(u[m], s.initial[m]), 100 * kExplicitTolerance) << "morphogen " << m;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Shapes, ExplicitStep,
                         ::testing::Values("shape:sphere", "shape:square", "shape:octagonal-prism"),
                         ShapeName);

TEST(ExplicitStep, TheFormulaIsCompiledWithUniformCoefficientsAsLiterals) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  OpenCLReactionDiffusion rd(compute(), domain, gray_scott(domain, 1e-3, Integrator::Forward, 1e-3, 1));
  ASSERT_EQ(rd.translated_reactions().size(), 2u);
  EXPECT_NE(rd.translated_reactions()[1].find("0.06f"), std::string::npos) << rd.translated_reactions()[1];  // k
  EXPECT_NE(rd.translated_reactions()[1].find("rd_c0"), std::string::npos) << rd.translated_reactions()[1];  // F
}

// The explicit integrator's two state halves take turns as the current one, so after an odd number
// of sub-steps the newest state lives in the half the backend started without. Every reader and
// writer must follow it: one step of three sub-steps reads back as three sub-steps of the double
// loop, the saved state is that state; values set then are what the device statistics see (a state
// far from the stale half's, so a statistic of the wrong half shows) and what the next step starts
// from; a filled layer reads back filled.
TEST(ExplicitStep, EveryReaderAndWriterFollowsTheCurrentHalfOfTheDoubleBuffer) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  const int n = domain.vertex_count;
  const double D_v = 1e-3;
  const double h = 0.8 * stable_step(domain, 2.0 * D_v);
  const ReactionDiffusionSystem s = gray_scott(domain, D_v, Integrator::Forward, 3 * h, 3);
  OpenCLReactionDiffusion rd(compute(), domain, s);
  rd.step();
  const auto reference = explicit_reference(s);
  const SimulationState saved = rd.save_state();
  for (int m = 0; m < 2; ++m) {
    const IntrinsicVertexData<double> device = rd.field_values(m);
    EXPECT_LT(max_difference(device, reference[m]), kExplicitTolerance * std::max(1.0, largest_magnitude(reference[m])))
        << "morphogen " << m;
    EXPECT_GT(max_difference(reference[m], s.initial[m]), 100 * kExplicitTolerance) << "morphogen " << m;
    EXPECT_EQ(saved.layers[static_cast<size_t>(m)].values(), device.values()) << "morphogen " << m;
  }

  // u now low and v high, where the step left u ~ 0.65 and v ~ 0.25 on average.
  ReactionDiffusionSystem restart = s;
  restart.initial = {random_values(n, 21, 0.0, 0.2), random_values(n, 22, 0.6, 1.0)};
  for (int m = 0; m < 2; ++m) {
    rd.set_field(restart.initial[static_cast<size_t>(m)], m);
    const double U = 0.5;
    const FieldStatistics expected = compute_field_statistics(restart.initial[static_cast<size_t>(m)], domain.vertex_mass, U);
    const FieldStatistics on_device = rd.field_statistics(U, m);
    EXPECT_NEAR(on_device.mean, expected.mean, 1e-5 * std::abs(expected.mean)) << "morphogen " << m;
    for (size_t c = 0; c < expected.coverage.size(); ++c)
      EXPECT_NEAR(on_device.coverage[c], expected.coverage[c], 1e-5) << "morphogen " << m << " coverage " << c;
  }
  rd.step();
  const auto from_restart = explicit_reference(restart);
  for (int m = 0; m < 2; ++m)
    EXPECT_LT(max_difference(rd.field_values(m), from_restart[m]),
              kExplicitTolerance * std::max(1.0, largest_magnitude(from_restart[m])))
        << "morphogen " << m << " after set_field";
  rd.fill_field(0.25, 1);
  for (double x : rd.field_values(1)) ASSERT_EQ(x, 0.25);
  EXPECT_EQ(rd.damaged_canaries(), std::vector<std::string>{});
}

class ImexStep : public ::testing::TestWithParam<ImexSolver> {};

TEST_P(ImexStep, MatchesAnEigenFactorizationOnTheHost) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  // A step 20x the explicit stability bound: only an implicit diffusion solve survives it.
  const double D_v = 1e-3;
  const ReactionDiffusionSystem s =
      gray_scott(domain, D_v, Integrator::Imex, 20 * stable_step(domain, 2 * D_v), 1);
  OpenCLReactionDiffusionOptions options;
  options.imex_solver = GetParam();
  const auto device = one_step(domain, s, options);
  const auto reference = imex_reference(s);
  for (int m = 0; m < 2; ++m) {
    EXPECT_LT(max_difference(device[m], reference[m]), kImexTolerance) << "morphogen " << m;
    EXPECT_GT(max_difference(reference[m], s.initial[m]), 100 * kImexTolerance) << "morphogen " << m;
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, ImexStep,
                         ::testing::Values(ImexSolver::DeviceConjugateGradients, ImexSolver::HostFactorization),
                         SolverName);

// Held vertices: every seventh vertex keeps its value exactly (as a float) through several steps,
// and the free vertices next to them follow the double loop, which sees the held values.
TEST(ReactionDiffusionDirichlet, HeldVerticesKeepTheirValuesAndTheRestFollows) {
  const SurfaceDomain& domain = domain_of("shape:square");
  const int n = domain.vertex_count;
  for (const Integrator integrator : {Integrator::Forward, Integrator::Imex}) {
    for (const ImexSolver solver : {ImexSolver::DeviceConjugateGradients, ImexSolver::HostFactorization}) {
      if (integrator == Integrator::Forward && solver == ImexSolver::HostFactorization) continue;
      const double h = 0.8 * stable_step(domain, 2e-3);
      ReactionDiffusionSystem s = integrator == Integrator::Forward
                                      ? gray_scott(domain, 1e-3, integrator, 2 * h, 2)
                                      : gray_scott(domain, 1e-3, integrator, 10 * h, 1);
      s.fixed.assign(static_cast<size_t>(n), 0);
      for (int i = 0; i < n; i += 7) s.fixed[static_cast<size_t>(i)] = 1;
      OpenCLReactionDiffusionOptions options;
      options.imex_solver = solver;
      OpenCLReactionDiffusion rd(compute(), domain, s, options);
      rd.step();
      const auto reference = integrator == Integrator::Forward ? explicit_reference(s) : imex_reference(s);
      for (int m = 0; m < 2; ++m) {
        const IntrinsicVertexData<double> u = rd.field_values(m);
        EXPECT_LT(max_difference(u, reference[m]), kImexTolerance) << "morphogen " << m;
      }
      rd.run(4);
      for (int m = 0; m < 2; ++m) {
        const IntrinsicVertexData<double> u = rd.field_values(m);
        for (int i = 0; i < n; i += 7)
          ASSERT_EQ(u[i], static_cast<double>(static_cast<float>(s.initial[m][i]))) << "morphogen " << m << " vertex " << i;
      }
    }
  }
}

// Planted faults: each must change the result well beyond the tolerance of the comparison above.
TEST(ReactionDiffusionFaults, SwapDiffusionAndNoFeedChangeTheStep) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  for (const Integrator integrator : {Integrator::Forward, Integrator::Imex}) {
    const double h = 0.8 * stable_step(domain, 2e-3);
    const ReactionDiffusionSystem s = gray_scott(domain, 1e-3, integrator, integrator == Integrator::Forward ? 2 * h : 10 * h,
                                                 integrator == Integrator::Forward ? 2 : 1);
    const auto clean = one_step(domain, s);
    for (const char* fault : {"-DPHYSARUM_FAULT_RD_SWAP_DIFFUSION", "-DPHYSARUM_FAULT_RD_NO_FEED"}) {
      OpenCLReactionDiffusionOptions options;
      options.build_options = fault;
      const auto faulty = one_step(domain, s, options);
      EXPECT_GT(std::max(max_difference(faulty[0], clean[0]), max_difference(faulty[1], clean[1])),
                100 * kExplicitTolerance)
          << fault;
    }
  }
}

TEST(ReactionDiffusionInputs, BadFormulasAndSizesAreRefusedWithWhere) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  ReactionDiffusionSystem s = gray_scott(domain, 1e-3, Integrator::Forward, 1e-3, 1);
  s.reaction[1] = "u*v^2 - (F+kk)*v";
  try {
    OpenCLReactionDiffusion rd(compute(), domain, s);
    FAIL() << "an unknown name was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'kk'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("position 12"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("morphogen 'v'"), std::string::npos) << e.what();
  }
  s = gray_scott(domain, 1e-3, Integrator::Forward, 1e-3, 1);
  s.initial[1].values().pop_back();
  EXPECT_THROW(OpenCLReactionDiffusion(compute(), domain, s), InputError);
  s = gray_scott(domain, 1e-3, Integrator::Forward, 1e-3, 1);
  s.stiffness[1].column[0] = s.stiffness[1].column[1];
  EXPECT_THROW(OpenCLReactionDiffusion(compute(), domain, s), InputError);
}

// A uniform steady state stays put: (u, v) = (1, 0) for Gray-Scott (R = 0 there and K 1 = 0).
TEST(ReactionDiffusionSteadyState, GrayScottStaysAtOneZero) {
  const SurfaceDomain& domain = domain_of("shape:sphere");
  ReactionDiffusionSystem s = gray_scott(domain, 1e-3, Integrator::Forward,
                                         2 * 0.8 * stable_step(domain, 2e-3), 2);
  s.initial = {IntrinsicVertexData<double>(static_cast<size_t>(domain.vertex_count), 1.0),
               IntrinsicVertexData<double>(static_cast<size_t>(domain.vertex_count), 0.0)};
  OpenCLReactionDiffusion rd(compute(), domain, s);
  rd.run(1000);
  EXPECT_LT(max_difference(rd.field_values(0), s.initial[0]), 1e-6);
  EXPECT_LT(max_difference(rd.field_values(1), s.initial[1]), 1e-6);
  EXPECT_EQ(rd.steps_taken(), 1000);
}

}  // namespace
}  // namespace physarum::opencl
