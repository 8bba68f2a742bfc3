// Competing species in the reference simulation (common/model/species.hpp, reference/agent_simulation.hpp): one
// species reading its own layer is the base model bit for bit; each layer's steady mean is its own
// species' U (Eq. 5 with that species' count and rates: deposits go only into its own layer); a
// negative cross term makes the species avoid each other (the layers' correlation drops); and row i
// of the sensing matrix is what species i reads (an asymmetric matrix tells the two orientations
// apart).
#include "common/setup/agent_inputs.hpp"
#include "common/simulation/field_statistics.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "reference/agent_simulation.hpp"
#include "loaded_scene.hpp"
#include "species_steady_means.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

json square_scene(int agents) {
  return {{"mesh", "shape:square"},   {"agents", agents},      {"time_step", 0.02},   {"sensor_distance", 0.05},
          {"sensor_angle", 22.5},     {"move_rate", 0.5},      {"turn_rate", 180.0},  {"turn_frequency", 20.0},
          {"deposit_rate", 1.0},      {"decay_rate", 1.0},     {"diffuse_rate", 0.0002}, {"mean_lifetime", 1.0},
          {"max_circumradius", 0.04}, {"seed", 3}};
}

using Loaded = testing::LoadedScene;
Loaded load(const json& j) { return testing::load_scene_json(j); }

TEST(SpeciesReference, OneSpeciesReadingItsOwnLayerIsTheBaseModelBitForBit) {
  json with = square_scene(300);
  with["species"] = {{{"agents", 300}}};
  with["sensing"] = {{1.0}};
  const Loaded base = load(square_scene(300));
  const Loaded one = load(with);
  ReferenceAgentSimulation a(base.surface.domain, base.arrays.parameters, base.arrays.controls, simulation_settings(base.scene));
  ReferenceAgentSimulation b(one.surface.domain, one.arrays.species, one.arrays.controls, simulation_settings(one.scene));
  EXPECT_EQ(b.dynamic_layer_count(), 1);
  for (int s = 0; s < 40; ++s) a.step(), b.step();
  EXPECT_EQ(a.field(0), b.field(0));  // exact: the same operations in the same order
  EXPECT_EQ(a.agents().position, b.agents().position);
  EXPECT_EQ(a.agents().heading, b.agents().heading);
}

// Pearson correlation of two fields weighted by the vertex masses.
double weighted_correlation(const IntrinsicVertexData<double>& x, const IntrinsicVertexData<double>& y,
                            const IntrinsicVertexData<double>& mass) {
  const double mx = area_weighted_mean(x, mass), my = area_weighted_mean(y, mass);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t v = 0; v < x.size(); ++v) {
    sxy += mass[v] * (x[v] - mx) * (y[v] - my);
    sxx += mass[v] * (x[v] - mx) * (x[v] - mx);
    syy += mass[v] * (y[v] - my) * (y[v] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

TEST(SpeciesReference, EachLayersSteadyMeanIsItsOwnSpeciesU) {
  json j = square_scene(0);
  j.erase("agents");
  testing::add_two_unequal_species(j);
  const Loaded l = load(j);
  const SurfaceDomain& domain = l.surface.domain;
  ReferenceAgentSimulation sim(domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene));
  testing::expect_each_layer_at_its_species_u(sim, domain, [&](int layer, double) {
    return area_weighted_mean(sim.field(layer), domain.vertex_mass);
  });
}

// The mass-weighted correlation of the two layers, time-averaged over the last 2 s of 5 s.
double layer_correlation(double cross) {
  json j = square_scene(0);
  j.erase("agents");
  j["species"] = {{{"agents", 1500}}, {{"agents", 1500}}};
  j["sensing"] = {{1.0, cross}, {cross, 1.0}};
  j["mean_lifetime"] = nullptr;
  const Loaded l = load(j);
  ReferenceAgentSimulation sim(l.surface.domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene));
  double sum = 0.0;
  int samples = 0;
  for (int s = 0; s < 250; ++s) {
    sim.step();
    if (s >= 150 && s % 10 == 0) sum += weighted_correlation(sim.field(0), sim.field(1), l.surface.domain.vertex_mass), ++samples;
  }
  return sum / samples;
}

TEST(SpeciesReference, ANegativeCrossTermSeparatesTheSpecies) {
  const double independent = layer_correlation(0.0);
  const double repelling = layer_correlation(-1.0);
  std::cout << "correlation of the two layers: cross term 0: " << independent << ", cross term -1: " << repelling << "\n";
  // Independent species lay uncorrelated networks (|r| small); repelling ones avoid each other's
  // trails, so their layers are anti-correlated: a clear drop, stated as 0.2.
  EXPECT_LT(repelling, independent - 0.2);
}

TEST(SpeciesReference, RowIOfTheMatrixIsWhatSpeciesIReads) {
  // Standing agents (move rate 0, no deposits, no turnover) that decide every step. Layer 1 is a
  // ramp, layer 0 is zero. With m = [[0, 1], [0, 0]] species 0 reads the ramp and turns toward it;
  // species 1 reads 0 everywhere (a tie: straight on) and keeps its heading exactly. The transposed
  // matrix would make species 0 read nothing.
  json j = square_scene(0);
  j.erase("agents");
  j["maps"] = {{"ramp_x", {{"axis", "x"}}}};
  j["move_rate"] = 0.0;
  j["deposit_rate"] = 0.0;
  j["diffuse_rate"] = 0.0;
  j["mean_lifetime"] = nullptr;
  j["turn_frequency"] = 50.0;  // one decision per 0.02 s step
  j["species"] = {{{"agents", 200}}, {{"agents", 200}}};
  j["sensing"] = {{0.0, 1.0}, {0.0, 0.0}};
  const Loaded l = load(j);
  ReferenceAgentSimulation sim(l.surface.domain, l.arrays.species, l.arrays.controls, simulation_settings(l.scene));
  const EvaluatedMaps maps = evaluate_maps(l.scene.maps, l.surface, "test");
  sim.set_field(maps.scalar_map("ramp_x"), 1);
  const Agents before = sim.agents();
  sim.step();
  // A zero-length move still re-expresses the heading of an agent standing on an edge in the next
  // face's frame; only agents on their own face compare headings.
  int turned0 = 0, turned1 = 0, same_face = 0;
  for (int a = 0; a < 400; ++a) {
    if (sim.agents().face[a] != before.face[a]) continue;
    ++same_face;
    // A turn is 3.6 degrees (turn rate / frequency); the walk of length 0 may round the heading.
    const bool turned = (sim.agents().heading[a] - before.heading[a]).norm() > 1e-6;
    (a < 200 ? turned0 : turned1) += turned ? 1 : 0;
  }
  EXPECT_GT(same_face, 350);
  // On a ramp only an agent heading within the sensor angle of uphill sees its centre strongest; the
  // rest (about 1 - 2 x 22.5/360 of them, less the few whose sensors leave the square) turn.
  EXPECT_GT(turned0, 120);
  EXPECT_EQ(turned1, 0);
}

// `physarum run` on the reference writes every species' layer: pheromone_0, pheromone_1 beside
// "pheromone" (layer 0, for one-species readers), in pheromone.ply and fields_full.ply; the two
// layers differ (two species, different deposits), and a one-species run has no pheromone_0.
TEST(SpeciesReference, RunWritesOnePropertyPerSpecies) {
  TempDir dir;
  json j = square_scene(0);
  j.erase("agents");
  j["species"] = {{{"agents", 300}}, {{"agents", 100}, {"deposit_rate", 4.0}}};
  j["sensing"] = {{1.0, -0.5}, {-0.5, 1.0}};
  j["steps"] = 20;
  const std::string path = (dir.path / "species.json").string();
  std::ofstream(path) << j.dump(2);
  const auto r = testing::run_physarum("run " + testing::quoted(path) + " --backend reference --out " +
                                       testing::quoted(dir.path / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* file : {"pheromone.ply", "fields_full.ply"}) {
    const PlyFields ply = read_ply_fields((dir.path / "out" / file).string());
    EXPECT_EQ(ply.property("pheromone"), ply.property("pheromone_0")) << file;
    EXPECT_NE(ply.property("pheromone_0"), ply.property("pheromone_1")) << file;
    EXPECT_EQ(ply.properties.count("pheromone_2"), 0u) << file;
  }
  json one = square_scene(50);
  one["steps"] = 2;
  std::ofstream((dir.path / "one.json").string()) << one.dump(2);
  ASSERT_EQ(testing::run_physarum("run " + testing::quoted(dir.path / "one.json") + " --backend reference --out " +
                                  testing::quoted(dir.path / "one"))
                .exit_code,
            0);
  EXPECT_EQ(read_ply_fields((dir.path / "one" / "pheromone.ply").string()).properties.count("pheromone_0"), 0u);
}

}  // namespace
}  // namespace physarum
