// Static field layers (common/simulation/simulation_backend.hpp) on both backends: fixed per-vertex maps after
// the dynamic layers, which step() never advances and the agents never deposit into.
//
// Each check runs on the reference and on the OpenCL simulation. A static layer keeps its values
// over a run (the reference exactly; the device as floats), adding one leaves the dynamic layer's
// run bit for bit as it was, its statistics are the mass-weighted mean and coverage computed here
// independently, and bad indices, sizes and values are refused with InputError naming the layer.
#include "common/setup/agent_inputs.hpp"
#include "common/base/errors.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"
#include "delaunay_domain.hpp"
#include "model_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace physarum {
namespace {

enum class Backend { Reference, OpenCL };

const opencl::ComputeContext& compute() {
  static const opencl::ComputeContext c = opencl::make_compute_context("");
  return c;
}

const SurfaceDomain& sphere() {
  static const SurfaceDomain d = testing::delaunay_domain("shape:sphere");
  return d;
}

// The shared test model with turnover (respawns exercise the whole step).
Scene scene(Integrator integrator = Integrator::Forward) {
  return testing::model_scene(3000, 0.01, 0.2, integrator);
}

std::unique_ptr<SimulationBackend> make_simulation(Backend backend, const Scene& s) {
  if (backend == Backend::Reference)
    return std::make_unique<ReferenceAgentSimulation>(sphere(), constant_parameters(s, sphere()), simulation_settings(s));
  return std::make_unique<opencl::OpenCLAgentSimulation>(compute(), sphere(), constant_parameters(s, sphere()), simulation_settings(s));
}

// A non-uniform field: a linear function of the vertex index plus a wiggle, all values distinct.
IntrinsicVertexData<double> non_uniform_field(int vertex_count) {
  IntrinsicVertexData<double> v(static_cast<size_t>(vertex_count));
  for (int i = 0; i < vertex_count; ++i) v[static_cast<size_t>(i)] = 1.0 + 1e-3 * i + 0.5 * std::sin(0.37 * i);
  return v;
}

// What a backend stores of `values`: the reference doubles as they are, the device floats.
IntrinsicVertexData<double> as_stored(Backend backend, IntrinsicVertexData<double> values) {
  if (backend == Backend::OpenCL)
    for (double& x : values) x = static_cast<double>(static_cast<float>(x));
  return values;
}

void expect_canaries_intact(const SimulationBackend& sim) {
  if (const auto* device = dynamic_cast<const opencl::OpenCLAgentSimulation*>(&sim)) {
    EXPECT_TRUE(device->damaged_canaries().empty());
  }
}

const char* name(Backend backend) { return backend == Backend::Reference ? "reference" : "opencl"; }

// ---- counts and indices ----

void expect_counts(Backend backend) {
  auto sim = make_simulation(backend, scene());
  const int n = sphere().vertex_count;
  EXPECT_EQ(sim->layer_count(), 1);
  EXPECT_EQ(sim->dynamic_layer_count(), 1);
  EXPECT_EQ(sim->add_static_layer(non_uniform_field(n)), 1);
  EXPECT_EQ(sim->add_static_layer(IntrinsicVertexData<double>(static_cast<size_t>(n), 2.0)), 2);
  EXPECT_EQ(sim->layer_count(), 3);
  EXPECT_EQ(sim->dynamic_layer_count(), 1);
  EXPECT_EQ(sim->field_values(1).values(), as_stored(backend, non_uniform_field(n)).values());
  EXPECT_EQ(sim->field_values(2).values(), std::vector<double>(static_cast<size_t>(n), 2.0));
}

TEST(StaticLayers, ReferenceCountsDynamicAndStaticLayers) { expect_counts(Backend::Reference); }
TEST(StaticLayers, OpenCLCountsDynamicAndStaticLayers) { expect_counts(Backend::OpenCL); }

// ---- a static layer keeps its values ----

void expect_unchanged_after_steps(Backend backend, Integrator integrator) {
  auto sim = make_simulation(backend, scene(integrator));
  const int n = sphere().vertex_count;
  const IntrinsicVertexData<double> values = non_uniform_field(n);
  const int first = sim->add_static_layer(values);
  const int second = sim->add_static_layer(IntrinsicVertexData<double>(static_cast<size_t>(n), 0.0));
  const IntrinsicVertexData<double> pheromone_before = sim->field_values(0);
  sim->run(20);
  EXPECT_EQ(sim->field_values(first).values(), as_stored(backend, values).values()) << name(backend);
  EXPECT_EQ(sim->field_values(second).values(), std::vector<double>(static_cast<size_t>(n), 0.0)) << name(backend);
  // The dynamic layer did move (the agents deposited into it), so the run did something.
  EXPECT_NE(sim->field_values(0), pheromone_before) << name(backend);
  expect_canaries_intact(*sim);
}

TEST(StaticLayers, ReferenceStaticLayerIsUnchangedAfterTwentyStepsForwardEuler) {
  expect_unchanged_after_steps(Backend::Reference, Integrator::Forward);
}
TEST(StaticLayers, ReferenceStaticLayerIsUnchangedAfterTwentyStepsBackwardEuler) {
  expect_unchanged_after_steps(Backend::Reference, Integrator::Backward);
}
TEST(StaticLayers, OpenCLStaticLayerIsUnchangedAfterTwentyStepsForwardEuler) {
  expect_unchanged_after_steps(Backend::OpenCL, Integrator::Forward);
}
TEST(StaticLayers, OpenCLStaticLayerIsUnchangedAfterTwentyStepsBackwardEuler) {
  expect_unchanged_after_steps(Backend::OpenCL, Integrator::Backward);
}

// ---- adding one changes nothing else ----

void expect_dynamic_layer_unaffected(Backend backend) {
  const Scene s = scene();
  const double U = uniform_steady_state(s, sphere().total_area);
  auto plain = make_simulation(backend, s);
  auto with_static = make_simulation(backend, s);
  // A static layer far from the pheromone's values, so sensing it instead would steer differently.
  IntrinsicVertexData<double> values = non_uniform_field(sphere().vertex_count);
  for (double& x : values) x *= 100.0 * U;
  with_static->add_static_layer(values);
  plain->fill_field(U);
  with_static->fill_field(U);
  plain->run(25);
  with_static->run(25);
  EXPECT_EQ(plain->field_values(0).values(), with_static->field_values(0).values()) << name(backend);
  EXPECT_EQ(plain->agent_faces(), with_static->agent_faces()) << name(backend);
  const FieldStatistics a = plain->field_statistics(U), b = with_static->field_statistics(U);
  EXPECT_EQ(a.mean, b.mean) << name(backend);
  EXPECT_EQ(a.coverage, b.coverage) << name(backend);
  expect_canaries_intact(*with_static);
}

TEST(StaticLayers, ReferenceAddingAStaticLayerLeavesTheDynamicLayerBitIdentical) {
  expect_dynamic_layer_unaffected(Backend::Reference);
}
TEST(StaticLayers, OpenCLAddingAStaticLayerLeavesTheDynamicLayerBitIdentical) {
  expect_dynamic_layer_unaffected(Backend::OpenCL);
}

// ---- statistics ----

// The mass-weighted mean and the mass fraction strictly above a threshold, in double, from the
// domain's masses (independent of common/simulation/field_statistics).
double weighted_mean(const IntrinsicVertexData<double>& values) {
  const IntrinsicVertexData<double>& m = sphere().vertex_mass;
  double sum = 0.0, mass = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    sum += m[i] * values[i];
    mass += m[i];
  }
  return sum / mass;
}

void expect_statistics(Backend backend) {
  auto sim = make_simulation(backend, scene());
  const int n = sphere().vertex_count;
  // Backends store floats on the device: compare with the mean of what is stored, to 1e-6 (the
  // float reduction's rounding).
  const double tolerance = backend == Backend::Reference ? 1e-12 : 1e-6;
  const IntrinsicVertexData<double> values = non_uniform_field(n);
  const int layer = sim->add_static_layer(values);
  sim->run(5);
  const double U = 1.7;
  const double expected_mean = weighted_mean(as_stored(backend, values));
  const FieldStatistics stats = sim->field_statistics(U, layer);
  EXPECT_NEAR(stats.mean / expected_mean, 1.0, tolerance) << name(backend);
  EXPECT_EQ(stats.U, U);

  // 0 on the even vertices, 3U on the odd ones: every coverage threshold (0.5U, U, 2U) splits them
  // the same way, so each coverage is the odd vertices' share of the mass.
  IntrinsicVertexData<double> halves(static_cast<size_t>(n), 0.0);
  double odd_mass = 0.0, total_mass = 0.0;
  for (size_t i = 0; i < halves.size(); ++i) {
    total_mass += sphere().vertex_mass[i];
    if (i % 2 == 1) {
      halves[i] = 3.0 * U;
      odd_mass += sphere().vertex_mass[i];
    }
  }
  sim->set_field(halves, layer);
  sim->run(5);
  const FieldStatistics split = sim->field_statistics(U, layer);
  const double fraction = odd_mass / total_mass;
  ASSERT_GT(fraction, 0.3);
  ASSERT_LT(fraction, 0.7);
  for (size_t k = 0; k < kCoverageMultiples.size(); ++k)
    EXPECT_NEAR(split.coverage[k] / fraction, 1.0, tolerance) << name(backend) << " coverage " << k;
  EXPECT_NEAR(split.mean / (3.0 * U * fraction), 1.0, tolerance) << name(backend);
  expect_canaries_intact(*sim);
}

TEST(StaticLayers, ReferenceStatisticsAreTheMassWeightedMeanAndCoverage) { expect_statistics(Backend::Reference); }
TEST(StaticLayers, OpenCLStatisticsAreTheMassWeightedMeanAndCoverage) { expect_statistics(Backend::OpenCL); }

// ---- fill ----

void expect_fill(Backend backend) {
  auto sim = make_simulation(backend, scene());
  const int n = sphere().vertex_count;
  const int layer = sim->add_static_layer(non_uniform_field(n));
  sim->fill_field(2.5, layer);
  sim->run(10);
  EXPECT_EQ(sim->field_values(layer).values(), std::vector<double>(static_cast<size_t>(n), 2.5)) << name(backend);
  EXPECT_NEAR(sim->field_statistics(1.0, layer).mean / 2.5, 1.0, 1e-6) << name(backend);
  expect_canaries_intact(*sim);
}

TEST(StaticLayers, ReferenceFillFieldSetsAStaticLayerEverywhere) { expect_fill(Backend::Reference); }
TEST(StaticLayers, OpenCLFillFieldSetsAStaticLayerEverywhere) { expect_fill(Backend::OpenCL); }

// ---- errors ----

void expect_input_error(const std::function<void()>& call, const std::string& message_part, const std::string& what) {
  try {
    call();
    ADD_FAILURE() << what << ": no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos)
        << what << ": the message '" << e.what() << "' does not say '" << message_part << "'";
  }
}

void expect_errors(Backend backend) {
  auto sim = make_simulation(backend, scene());
  SimulationBackend& s = *sim;
  const int n = sphere().vertex_count;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string b = name(backend);
  IntrinsicVertexData<double> short_field(static_cast<size_t>(n - 1), 1.0);
  IntrinsicVertexData<double> with_nan = non_uniform_field(n);
  with_nan[static_cast<size_t>(n / 2)] = nan;
  IntrinsicVertexData<double> with_infinity = non_uniform_field(n);
  with_infinity[0] = std::numeric_limits<double>::infinity();

  expect_input_error([&] { s.add_static_layer(short_field); }, "field layer 1", b + " add_static_layer wrong size");
  expect_input_error([&] { s.add_static_layer(with_nan); }, "field layer 1", b + " add_static_layer NaN");
  expect_input_error([&] { s.add_static_layer(with_infinity); }, "field layer 1", b + " add_static_layer infinity");
  EXPECT_EQ(s.layer_count(), 1) << b << ": a refused layer was added";

  const int layer = s.add_static_layer(non_uniform_field(n));
  ASSERT_EQ(layer, 1);
  expect_input_error([&] { s.set_field(short_field, layer); }, "field layer 1", b + " set_field wrong size");
  expect_input_error([&] { s.set_field(with_nan, layer); }, "field layer 1", b + " set_field NaN");
  expect_input_error([&] { s.set_field(non_uniform_field(n), 2); }, "field layer 2", b + " set_field index");
  expect_input_error([&] { s.set_field(non_uniform_field(n), -1); }, "field layer -1", b + " set_field -1");
  expect_input_error([&] { s.fill_field(nan, layer); }, "field layer 1", b + " fill_field NaN");
  expect_input_error([&] { s.fill_field(1.0, 2); }, "field layer 2", b + " fill_field index");
  expect_input_error([&] { s.field_values(2); }, "field layer 2", b + " field_values index");
  expect_input_error([&] { s.field_statistics(1.0, 5); }, "field layer 5", b + " field_statistics index");
  // Refused writes left the layer as it was.
  EXPECT_EQ(s.field_values(layer).values(), as_stored(backend, non_uniform_field(n)).values()) << b;
  // The dynamic layer is checked the same way.
  expect_input_error([&] { s.set_field(with_nan, 0); }, "field layer 0", b + " set_field NaN on layer 0");
}

TEST(StaticLayers, ReferenceRefusesBadSizesIndicesAndValues) { expect_errors(Backend::Reference); }
TEST(StaticLayers, OpenCLRefusesBadSizesIndicesAndValues) { expect_errors(Backend::OpenCL); }

}  // namespace
}  // namespace physarum
