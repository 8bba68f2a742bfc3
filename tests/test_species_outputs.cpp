// What `physarum run` writes for competing species (common/setup/species_statistics.hpp,
// common/output/preview_image.hpp): a preview where each species' network shows in its own colour, stats.csv
// columns mean_i,U_i per species with U_i from Eq. 5 (derived here from the scene's numbers and the
// reported area), and run.json's species_layers. One species keeps its outputs as they were.
#include "common/base/errors.hpp"
#include "common/output/preview_image.hpp"
#include "pheromone_test_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

// Two species on the two halves of a square: every surface pixel is in one species' colour (plus the
// dark base), scaled by the shading. The shading scales all channels alike, so the ratio green/red
// of species 0's pixels is that of base + colour 0, and blue/green that of base + colour 1.
TEST(SpeciesPreview, EachSpeciesShowsInItsOwnColour) {
  const InputMesh mesh = testing::make_square_grid(24);
  InputVertexData<double> left(mesh.positions.size()), right(mesh.positions.size());
  for (size_t v = 0; v < left.size(); ++v) {
    left[v] = mesh.positions[v].x() < 0.5 ? 1.0 : 0.0;
    right[v] = 1.0 - left[v];
  }
  FieldColoring coloring;
  coloring.high = 1.0;  // a layer at 1 is at the top of its range: its full colour
  PreviewOptions options;
  options.width = 240;
  options.height = 180;
  const RgbImage image = render_species_preview(mesh, {left, right}, {coloring, coloring}, options);
  const std::array<double, 3> c0 = species_colour(0), c1 = species_colour(1);
  const double base = 0.06, base_blue = 0.08;
  const double green_over_red0 = (base + c0[1]) / std::min(base + c0[0], 1.0);
  const double green_over_blue1 = (base + c1[1]) / std::min(base_blue + c1[2], 1.0);
  int species0 = 0, species1 = 0, surface = 0;
  for (size_t p = 0; p < image.pixels.size(); p += 3) {
    const int r = image.pixels[p], g = image.pixels[p + 1], b = image.pixels[p + 2];
    if (r == 255 && g == 255 && b == 255) continue;
    ++surface;
    if (r > 100 && r > 3 * b && std::abs(static_cast<double>(g) / r - green_over_red0) < 0.02) ++species0;
    if (b > 100 && b > 3 * r && std::abs(static_cast<double>(g) / b - green_over_blue1) < 0.02) ++species1;
  }
  ASSERT_GT(surface, 1000);
  // Each half is a good share of the picture; only the pixels along the seam between them mix.
  EXPECT_GT(species0, surface / 3);
  EXPECT_GT(species1, surface / 3);
  EXPECT_GT(species0 + species1, surface * 9 / 10);
  EXPECT_NE(c0, c1);

  EXPECT_THROW(render_species_preview(mesh, {left, right}, {coloring}, options), InputError);
  EXPECT_THROW(render_species_preview(mesh, {left, InputVertexData<double>{1.0}}, {coloring, coloring}, options),
               InputError);
}

json two_species_scene(int agents0, int agents1) {
  return {{"mesh", "shape:square"},   {"time_step", 0.02},      {"sensor_distance", 0.05}, {"sensor_angle", 22.5},
          {"move_rate", 0.5},         {"turn_rate", 180.0},     {"turn_frequency", 20.0},  {"deposit_rate", 1.0},
          {"decay_rate", 1.0},        {"diffuse_rate", 0.0002}, {"mean_lifetime", 2.0},    {"activation_time", 0.5},
          {"max_circumradius", 0.05}, {"seed", 3},              {"steps", 10},
          {"species", {{{"agents", agents0}}, {{"agents", agents1}, {"deposit_rate", 4.0}, {"decay_rate", 2.0}}}},
          {"sensing", {{1.0, -0.5}, {-0.5, 1.0}}}};
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(SpeciesRun, StatsCsvAndRunJsonReportEachSpecies) {
  TempDir dir;
  const std::string scene = (dir.path / "two.json").string();
  std::ofstream(scene) << two_species_scene(300, 100).dump(2);
  const auto r = testing::run_physarum("run " + testing::quoted(scene) + " --backend reference --out " +
                                       testing::quoted(dir.path / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json run = json::parse(read_text(dir.path / "out" / "run.json"));
  const double area = run["area"].get<double>();
  // Eq. 5 per species: U_i = N_i r_dep,i / (r_dec,i A) exp(-t_a / tau).
  const double U0 = 300 * 1.0 / (1.0 * area) * std::exp(-0.5 / 2.0);
  const double U1 = 100 * 4.0 / (2.0 * area) * std::exp(-0.5 / 2.0);

  std::stringstream csv(read_text(dir.path / "out" / "stats.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U,mean_0,U_0,mean_1,U_1");
  int rows = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> cells = split(line);
    ASSERT_EQ(cells.size(), 10u) << line;
    EXPECT_EQ(cells[1], cells[6]) << "mean is layer 0's mean";
    EXPECT_NEAR(std::stod(cells[7]) / U0, 1.0, 1e-12);
    EXPECT_NEAR(std::stod(cells[9]) / U1, 1.0, 1e-12);
    ++rows;
  }
  EXPECT_GE(rows, 2);

  ASSERT_EQ(run["species_layers"].size(), 2u);
  EXPECT_EQ(run["species_layers"][0]["agents"], 300);
  EXPECT_EQ(run["species_layers"][1]["agents"], 100);
  EXPECT_NEAR(run["species_layers"][1]["U"].get<double>() / U1, 1.0, 1e-12);
  EXPECT_NE(run["species_layers"][0]["preview_colour"], run["species_layers"][1]["preview_colour"]);
  EXPECT_EQ(run["species_layers"][0]["mean"], run["mean"]);

  // One species: the columns and keys of the base model only.
  json one = two_species_scene(0, 0);
  one.erase("species");
  one.erase("sensing");
  one["agents"] = 50;
  std::ofstream((dir.path / "one.json").string()) << one.dump(2);
  ASSERT_EQ(testing::run_physarum("run " + testing::quoted(dir.path / "one.json") + " --backend reference --out " +
                                  testing::quoted(dir.path / "one"))
                .exit_code,
            0);
  std::stringstream one_csv(read_text(dir.path / "one" / "stats.csv"));
  std::getline(one_csv, line);
  EXPECT_EQ(line, "time,mean,U,coverage_0.5U,coverage_1U,coverage_2U");
  EXPECT_FALSE(json::parse(read_text(dir.path / "one" / "run.json")).contains("species_layers"));
}

}  // namespace
}  // namespace physarum
