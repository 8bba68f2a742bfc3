// Cascaded patterns (Turk 1992; issue 21): a second Gray-Scott run starts from the first run's
// fields_full.ply (maps {"fields_full": ...} as the morphogens' "initial"), holds the first run's
// spots fixed through "dirichlet", and grows smaller spots between them with a quarter of the
// diffusion rates. Known answers:
//   - the held vertices end with the first run's values EXACTLY (the PLY stores floats; a float read
//     into a double and written again is the same float): nothing diffuses into a held vertex and
//     no noise or seed touches it;
//   - new spots appear: the second run has more spots than the first, and at least 3 of them hold
//     no held vertex (they grew in the gaps);
//   - the new spots are smaller: Gray-Scott's length scale goes as sqrt(D), so D / 4 halves a spot's
//     diameter and quarters its area; we require the median new spot's area to be below half the
//     median first-run spot's (a margin of 2 over the scaling answer, for the coarse mesh).
// Spots are the pieces of {v > 0.1} (common/pattern/pattern_segmentation.hpp): 0.1 is the freezing
// threshold of the scene too, well above the background (v = 0) and below a spot's plateau (~0.3).
// A run on another surface is refused, naming the file and the vertex counts.
#include "common/pattern/pattern_segmentation.hpp"
#include "common/mesh/ply_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kSpotThreshold = 0.1;

// A 0.7 m square (about 1,500 vertices): large spots from four seeds at 4 x Pearson's diffusion.
json first_stage() {
  return {{"mesh", "shape:square"},
          {"scale_to_area", 0.49},
          {"max_circumradius", 0.011},
          {"model", "gray-scott"},
          {"parameters", {{"F", 0.035}, {"k", 0.065}}},
          {"morphogens", {{"u", {{"diffusion", 8e-5}, {"initial", 1.0}}}, {"v", {{"diffusion", 4e-5}, {"initial", 0.0}}}}},
          {"initial", {{"noise", 0.01}, {"spots", {{"count", 3}, {"radius", 0.1}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}}},
          {"time_step", 1.0},
          {"integrator", "imex"},
          {"seed", 1}};
}

// The same surface, Pearson's diffusion (a quarter), seeded from the first stage with its spots held.
json second_stage(const fs::path& first_fields) {
  json s = first_stage();
  s["maps"] = {{"first_u", {{"fields_full", first_fields.string()}, {"property", "u"}}},
               {"first_v", {{"fields_full", first_fields.string()}, {"property", "v"}}},
               {"large_spots", {{"threshold", "first_v"}, {"at", kSpotThreshold}}}};
  s["morphogens"] = {{"u", {{"diffusion", 2e-5}, {"initial", "first_u"}}}, {"v", {{"diffusion", 1e-5}, {"initial", "first_v"}}}};
  s["initial"] = {{"noise", 0.01}, {"spots", {{"count", 16}, {"radius", 0.03}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}};
  s["dirichlet"] = {{"map", "large_spots"}};
  s["seed"] = 2;
  return s;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x.empty() ? 0.0 : x[x.size() / 2];
}

TEST(CascadedPatterns, TheFirstLayerStaysFrozenAndSmallerSpotsGrowBetween) {
  TempDir dir;
  std::ofstream(dir.path / "first.json") << first_stage().dump();
  const CommandResult first = run_physarum("run " + quoted(dir.path / "first.json") +
                                           " --backend reference --steps 3000 --texture-size 16 --out " + quoted(dir.path / "first"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const fs::path first_fields = dir.path / "first" / "fields_full.ply";
  std::ofstream(dir.path / "second.json") << second_stage(first_fields).dump();
  const CommandResult second = run_physarum("run " + quoted(dir.path / "second.json") +
                                            " --backend reference --steps 3000 --texture-size 16 --out " + quoted(dir.path / "second"));
  ASSERT_EQ(second.exit_code, 0) << second.err;

  const PlyFields a = read_ply_fields(first_fields.string());
  const PlyFields b = read_ply_fields((dir.path / "second" / "fields_full.ply").string());
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
  const std::vector<double>&ua = a.property("u"), &va = a.property("v"), &ub = b.property("u"), &vb = b.property("v");
  std::set<int> held;
  for (size_t i = 0; i < va.size(); ++i)
    if (va[i] >= kSpotThreshold) {
      held.insert(static_cast<int>(i));
      EXPECT_EQ(ub[i], ua[i]) << "held vertex " << i << ": u changed";
      EXPECT_EQ(vb[i], va[i]) << "held vertex " << i << ": v changed";
    }
  ASSERT_GT(held.size(), 20u) << "the first stage grew no spots to freeze";

  const PatternSegmentation spots_a = segment_pattern(a.mesh, InputVertexData<double>(va), kSpotThreshold);
  const PatternSegmentation spots_b = segment_pattern(b.mesh, InputVertexData<double>(vb), kSpotThreshold);
  std::vector<double> old_areas, new_areas;
  for (const PatternRegion& r : spots_a.regions) old_areas.push_back(r.area);
  for (const PatternRegion& r : spots_b.regions)
    if (std::none_of(r.vertices.begin(), r.vertices.end(), [&](int v) { return held.count(v) > 0; }))
      new_areas.push_back(r.area);
  RecordProperty("first_stage_spots", static_cast<int>(spots_a.regions.size()));
  RecordProperty("second_stage_spots", static_cast<int>(spots_b.regions.size()));
  RecordProperty("new_spots", static_cast<int>(new_areas.size()));
  RecordProperty("median_area_ratio", std::to_string(median(new_areas) / median(old_areas)));
  ASSERT_GE(spots_a.regions.size(), 2u);
  EXPECT_GT(spots_b.regions.size(), spots_a.regions.size());
  ASSERT_GE(new_areas.size(), 3u);
  EXPECT_LT(median(new_areas), 0.5 * median(old_areas))
      << "new spots: median area " << median(new_areas) << ", first stage's " << median(old_areas);
}

TEST(CascadedPatterns, AnEarlierRunOnAnotherSurfaceIsRefused) {
  TempDir dir;
  std::ofstream(dir.path / "first.json") << first_stage().dump();
  ASSERT_EQ(run_physarum("run " + quoted(dir.path / "first.json") +
                         " --backend reference --steps 1 --texture-size 16 --out " + quoted(dir.path / "first"))
                .exit_code,
            0);
  json other = second_stage(dir.path / "first" / "fields_full.ply");
  other["max_circumradius"] = 0.02;  // another intrinsic triangulation of the same square
  std::ofstream(dir.path / "second.json") << other.dump();
  const CommandResult r = run_physarum("run " + quoted(dir.path / "second.json") +
                                       " --backend reference --steps 1 --texture-size 16 --out " + quoted(dir.path / "second"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("fields_full.ply has "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("same mesh, scale_to_area, max_circumradius"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "second"));
}

}  // namespace
}  // namespace physarum::testing
