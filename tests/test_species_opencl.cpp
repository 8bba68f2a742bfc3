// Competing species on the OpenCL backend (opencl/agent_simulation.hpp, kernels/species.cl) against the
// reference and against known answers: one species through the species constructor runs the base
// model's kernels bit for bit; one step from identical two-species states agrees with the reference
// agent by agent and layer by layer (float32 against double); each layer's steady mean is its own
// species' U (Eq. 5); row i of the matrix is what species i reads. The planted fault
// species-matrix-transposed fails the last two comparisons it concerns.
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "opencl/planted_faults.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"
#include "loaded_scene.hpp"
#include "species_steady_means.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace physarum {
namespace {

using nlohmann::json;
using opencl::OpenCLAgentSimulation;
using opencl::OpenCLBackendOptions;
using testing::TempDir;

const opencl::ComputeContext& compute() {
  static const opencl::ComputeContext c = opencl::make_compute_context("");
  return c;
}

json square_scene() {
  return {{"mesh", "shape:square"},   {"time_step", 0.02},    {"sensor_distance", 0.05}, {"sensor_angle", 22.5},
          {"move_rate", 0.5},         {"turn_rate", 180.0},   {"turn_frequency", 20.0},  {"deposit_rate", 1.0},
          {"decay_rate", 1.0},        {"diffuse_rate", 0.0002}, {"mean_lifetime", 1.0},  {"max_circumradius", 0.04},
          {"seed", 3}};
}

using Loaded = testing::LoadedScene;
Loaded load(const json& j) { return testing::load_scene_json(j); }

OpenCLBackendOptions with_fault(const std::string& fault) {
  OpenCLBackendOptions options;
  options.build_options = opencl::fault_build_option(fault);
  return options;
}

// Two species with different rates (a parameter map in one) and an asymmetric matrix.
json two_species_scene() {
  json j = square_scene();
  j["maps"] = {{"ramp_x", {{"axis", "x"}}}};
  j["species"] = {{{"agents", 3000}, {"sensor_angle", 30.0}},
                  {{"agents", 2000}, {"deposit_rate", 2.0}, {"decay_rate", 0.5},
                   {"move_rate", {{"map", "ramp_x"}, {"range", {0.3, 0.6}}}}}};
  j["sensing"] = {{1.0, -0.8}, {0.3, 1.0}};
  return j;
}

TEST(SpeciesOpenCL, OneSpeciesThroughTheSpeciesConstructorIsTheBaseModelBitForBit) {
  json j = square_scene();
  j["agents"] = 2000;
  const Loaded l = load(j);
  const SurfaceDomain& d = l.surface.domain;
  const SimulationSettings settings = simulation_settings(l.scene);
  OpenCLAgentSimulation base(compute(), d, l.arrays.parameters, l.arrays.controls, settings);
  OpenCLAgentSimulation one(compute(), d, SpeciesSet::single(2000, l.arrays.parameters), l.arrays.controls, settings);
  EXPECT_EQ(one.dynamic_layer_count(), 1);
  base.run(30);
  one.run(30);
  EXPECT_EQ(base.field_values(), one.field_values());
  EXPECT_EQ(base.read_agents().position, one.read_agents().position);
}

struct SpeciesStepComparison {
  int agents = 0, mismatched = 0;
  double field_error = 0.0;  // max over layers of max |u_ocl - u_ref| / max |u_ref|
  std::string first_mismatch;
  bool canaries_damaged = false;
};

// tests/one_step_comparison.hpp for competing species: the reference develops a pattern, both
// backends get the device's float copy of its agents and layers and take one step.
SpeciesStepComparison compare_one_step(const Loaded& l, int warmup, const std::string& fault = "") {
  const SurfaceDomain& d = l.surface.domain;
  const SimulationSettings settings = simulation_settings(l.scene);
  ReferenceAgentSimulation developed(d, l.arrays.species, l.arrays.controls, settings);
  developed.run(warmup);
  OpenCLAgentSimulation device(compute(), d, l.arrays.species, l.arrays.controls, settings, with_fault(fault));
  device.write_agents(developed.agents());
  const int layers = developed.dynamic_layer_count();
  for (int s = 0; s < layers; ++s) device.set_field(developed.field(s), s);
  ReferenceAgentSimulation reference(d, l.arrays.species, l.arrays.controls, settings);
  reference.agents() = device.read_agents();
  for (int s = 0; s < layers; ++s) reference.set_field(device.field_values(s), s);

  reference.step();
  device.step();
  const Agents a = reference.agents(), b = device.read_agents();
  SpeciesStepComparison c;
  c.agents = a.count();
  for (int i = 0; i < a.count(); ++i) {
    const double dp = (a.position[i] - b.position[i]).norm(), dh = (a.heading[i] - b.heading[i]).norm();
    if (a.face[i] == b.face[i] && dp <= 1e-5 && dh <= 1e-5) continue;
    if (c.mismatched++ == 0)
      c.first_mismatch = "agent " + std::to_string(i) + ": |dp| " + std::to_string(dp) + ", |dh| " + std::to_string(dh);
  }
  for (int s = 0; s < layers; ++s) {
    const IntrinsicVertexData<double> ur = reference.field(s), uo = device.field_values(s);
    double scale = 0.0, err = 0.0;
    for (size_t v = 0; v < ur.size(); ++v) scale = std::max(scale, std::abs(ur[v])), err = std::max(err, std::abs(ur[v] - uo[v]));
    c.field_error = std::max(c.field_error, err / scale);
  }
  c.canaries_damaged = !device.damaged_canaries().empty();
  return c;
}

TEST(SpeciesOpenCL, OneStepAgreesWithTheReferenceAgentByAgentAndLayerByLayer) {
  const Loaded l = load(two_species_scene());
  const SpeciesStepComparison c = compare_one_step(l, 60);
  ASSERT_EQ(c.agents, 5000);
  std::cout << c.mismatched << " of " << c.agents << " agents disagree after one step; field " << c.field_error << "\n";
  // As for one species (test_opencl_simulation.cpp): float32 near-ties only, and the layers to
  // float rounding plus the deposits of those few agents.
  EXPECT_LE(c.mismatched, c.agents / 1000) << c.first_mismatch;
  EXPECT_LE(c.field_error, 2e-3);
  EXPECT_FALSE(c.canaries_damaged);
}

TEST(SpeciesOpenCL, PlantedFaultSpeciesMatrixTransposedIsCaughtInOneStep) {
  const SpeciesStepComparison c = compare_one_step(load(two_species_scene()), 60, "species-matrix-transposed");
  std::cout << "planted fault species-matrix-transposed: " << c.mismatched << " of " << c.agents << " agents disagree\n";
  EXPECT_GT(c.mismatched, c.agents / 100);
}

TEST(SpeciesOpenCL, EachLayersSteadyMeanIsItsOwnSpeciesU) {
  json j = square_scene();
  testing::add_two_unequal_species(j);
  const Loaded l = load(j);
  const SurfaceDomain& domain = l.surface.domain;
  OpenCLAgentSimulation sim(compute(), domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene));
  testing::expect_each_layer_at_its_species_u(
      sim, domain, [&](int layer, double U) { return sim.field_statistics(U, layer).mean; });
}

// Standing agents that decide every step; layer 1 a ramp, layer 0 zero; m = [[0, 1], [0, 0]]:
// species 0 reads the ramp and (most of it) turns, species 1 reads 0 everywhere and never turns.
// Returns the agents of species 0 and 1 that turned, among those still on their face.
std::pair<int, int> turned_by_species(const std::string& fault) {
  json j = square_scene();
  j["maps"] = {{"ramp_x", {{"axis", "x"}}}};
  j["move_rate"] = 0.0;
  j["deposit_rate"] = 0.0;
  j["diffuse_rate"] = 0.0;
  j["mean_lifetime"] = nullptr;
  j["turn_frequency"] = 50.0;
  j["species"] = {{{"agents", 200}}, {{"agents", 200}}};
  j["sensing"] = {{0.0, 1.0}, {0.0, 0.0}};
  const Loaded l = load(j);
  OpenCLAgentSimulation sim(compute(), l.surface.domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene),
                       with_fault(fault));
  sim.set_field(evaluate_maps(l.scene.maps, l.surface, "test").scalar_map("ramp_x"), 1);
  const Agents before = sim.read_agents();
  sim.step();
  const Agents after = sim.read_agents();
  int turned0 = 0, turned1 = 0;
  for (int a = 0; a < after.count(); ++a) {
    if (after.face[a] != before.face[a]) continue;  // read_agents returns agents in id order
    if ((after.heading[a] - before.heading[a]).norm() > 1e-5) (a < 200 ? turned0 : turned1)++;
  }
  return {turned0, turned1};
}

TEST(SpeciesOpenCL, RowIOfTheMatrixIsWhatSpeciesIReads) {
  const auto [turned0, turned1] = turned_by_species("");
  // About 1 - 2 x 22.5/360 of species 0 turns (reference test: test_species_reference.cpp).
  EXPECT_GT(turned0, 120);
  EXPECT_EQ(turned1, 0);
  // Transposed, species 0 reads column 0 (zeros): nobody turns.
  const auto [faulty0, faulty1] = turned_by_species("species-matrix-transposed");
  EXPECT_EQ(faulty0, 0);
  EXPECT_EQ(faulty1, 0);
}

TEST(SpeciesOpenCL, SpeciesWithSinksInDifferentPlacesAreRefused) {
  json j = square_scene();
  j["maps"] = {{"ramp_x", {{"axis", "x"}}}};
  j["species"] = {{{"agents", 100}}, {{"agents", 100}, {"mean_lifetime", {{"map", "ramp_x"}, {"range", {0.0, 2.0}}}}}};
  const Loaded l = load(j);
  try {
    OpenCLAgentSimulation sim(compute(), l.surface.domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("species 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace physarum
