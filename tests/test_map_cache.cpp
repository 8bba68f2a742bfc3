// The on-disk map cache (common/maps/map_cache.hpp, common/setup/cached_map_evaluation.hpp): a second evaluation
// of the same maps on the same surface reads every map back, bit for bit what evaluate_maps gives;
// changing a map's definition, a file it reads or the refinement recomputes exactly the maps that
// depend on the change; a corrupt or truncated entry is never trusted but recomputed and rewritten;
// an entry is used only for its own key, kind and count; the folder keeps to its size budget; and
// PHYSARUM_NO_CACHE turns it off.
#include "common/setup/cached_map_evaluation.hpp"
#include "common/maps/map_cache.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/output/ply_writer.hpp"
#include "common/setup/scene_surface.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

namespace physarum {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::TempDir;
using Names = std::vector<std::string>;

// Sets an environment variable for the life of the object (restoring what was there).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Writes a PLY with the property "w" = a * x + 1 on the square's input vertices.
void write_weight_ply(const fs::path& path, const PreparedSurface& surface, double a) {
  InputVertexData<double> w(static_cast<size_t>(surface.input.vertex_count()));
  for (int v = 0; v < surface.input.vertex_count(); ++v) w[v] = a * surface.input.positions[static_cast<size_t>(v)].x() + 1.0;
  write_field_ply(path.string(), surface.input, w, {}, "w");
}

// Five maps of every sort: a ramp, a map that reads it, a region, a PLY property and a vector map.
json five_maps() {
  return {{"ramp", {{"axis", "x"}}},
          {"scaled", {{"map", "ramp"}, {"range", {2.0, 4.0}}}},
          {"blob", {{"sphere", {{"center", {0.5, 0.5, 0.0}}, {"radius", 0.2}}}, {"falloff", 0.1}}},
          {"painted", {{"ply", "weight.ply"}, {"property", "w"}}},
          {"east", {{"direction", {1.0, 0.0, 0.0}}}}};
}

class MapCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    surface_ = prepare_surface(spec_);
    write_weight_ply(dir_.path / "weight.ply", surface_, 2.0);
  }

  // One cached evaluation of `maps` (parsed afresh, as a new run would) on `surface`.
  EvaluatedMaps evaluate(const json& maps, MapEvaluationReport& report, const PreparedSurface* surface = nullptr,
                         const SurfaceSpec* spec = nullptr) {
    const MapSet set = parse_maps(maps, dir_.path.string(), "scene.json");
    return cached_evaluate_maps(MapSources{set, maps, dir_.path.string(), spec ? *spec : spec_, "scene.json"},
                                surface ? *surface : surface_, cache_, &report);
  }
  EvaluatedMaps uncached(const json& maps, const PreparedSurface* surface = nullptr) {
    return evaluate_maps(parse_maps(maps, dir_.path.string(), "scene.json"), surface ? *surface : surface_, "scene.json");
  }
  fs::path entry_of(const json& maps, const std::string& name) {
    const MapSet set = parse_maps(maps, dir_.path.string(), "scene.json");
    return cache_.entry_path(map_cache_keys(MapSources{set, maps, dir_.path.string(), spec_, "scene.json"}, surface_).at(name));
  }
  size_t entries() const {
    size_t n = 0;
    if (fs::exists(cache_dir_.path / "maps"))
      for (const auto& e : fs::directory_iterator(cache_dir_.path / "maps")) n += e.path().extension() == ".map";
    return n;
  }

  TempDir dir_, cache_dir_;
  SurfaceSpec spec_{"shape:square", std::nullopt, std::nullopt, 0.0};
  PreparedSurface surface_;
  MapCache cache_{cache_dir_.path};
};

void expect_same_maps(const EvaluatedMaps& a, const EvaluatedMaps& b) {
  EXPECT_EQ(a.scalar, b.scalar);
  ASSERT_EQ(a.vector.size(), b.vector.size());
  for (const auto& [name, values] : a.vector) EXPECT_EQ(values, b.vector.at(name)) << name;
}

TEST_F(MapCacheTest, SecondEvaluationReadsEveryMapFromTheCacheBitForBit) {
  MapEvaluationReport first, second;
  const EvaluatedMaps computed = evaluate(five_maps(), first);
  EXPECT_TRUE(first.from_cache.empty());
  EXPECT_EQ(first.computed.size(), 5u);
  EXPECT_TRUE(first.notes.empty()) << first.notes.front();
  EXPECT_EQ(entries(), 5u);
  expect_same_maps(computed, uncached(five_maps()));

  const EvaluatedMaps cached = evaluate(five_maps(), second);
  EXPECT_TRUE(second.computed.empty());
  EXPECT_EQ(second.from_cache.size(), 5u);
  EXPECT_NE(second.summary().find("5 from cache"), std::string::npos) << second.summary();
  expect_same_maps(cached, uncached(five_maps()));
  // The PLY map's known values: w = 2x + 1 at every input vertex (the intrinsic vertex on it).
  for (int v = 0; v < surface_.input.vertex_count(); ++v)
    EXPECT_NEAR(cached.scalar.at("painted")[surface_.input_to_intrinsic[v]], 2.0 * surface_.input.positions[static_cast<size_t>(v)].x() + 1.0, 1e-6);
}

TEST_F(MapCacheTest, ChangingAMapRecomputesItAndEveryMapThatReadsIt) {
  MapEvaluationReport first, second;
  evaluate(five_maps(), first);
  json changed = five_maps();
  changed["ramp"] = {{"axis", "y"}};
  const EvaluatedMaps m = evaluate(changed, second);
  EXPECT_EQ(second.computed, (Names{"ramp", "scaled"}));
  EXPECT_EQ(second.from_cache, (Names{"blob", "east", "painted"}));
  expect_same_maps(m, uncached(changed));
  // scaled = 2 + 2 y now: at input vertex (x, y, 0).
  for (int v = 0; v < surface_.input.vertex_count(); ++v)
    EXPECT_NEAR(m.scalar.at("scaled")[surface_.input_to_intrinsic[v]], 2.0 + 2.0 * surface_.input.positions[static_cast<size_t>(v)].y(), 1e-12);
}

// Inline definitions (common/maps/inline_maps.hpp) are maps of their own: cached like named ones, and a
// change in the outer map alone leaves the inner one in the cache (a bias's "normalize" flag does
// not recompute the distance under it).
TEST_F(MapCacheTest, InlineMapsAreCachedAndAnOuterChangeKeepsTheInnerOne) {
  const json maps = json::parse(R"({"corner": {"sphere": {"center": [0, 0, 0], "radius": 0.1}},
      "away": {"gradient": {"geodesic_distance": {"from": "corner", "method": "fmm"}}}})");
  MapEvaluationReport first, second, third;
  evaluate(maps, first);
  EXPECT_EQ(first.computed, (Names{"corner", "away_gradient", "away"}));
  EXPECT_EQ(entries(), 3u);
  evaluate(maps, second);
  EXPECT_TRUE(second.computed.empty());
  EXPECT_EQ(second.from_cache.size(), 3u);
  json normalized = maps;
  normalized["away"]["normalize"] = true;
  const EvaluatedMaps m = evaluate(normalized, third);
  EXPECT_EQ(third.computed, (Names{"away"}));
  EXPECT_EQ(third.from_cache, (Names{"corner", "away_gradient"}));
  expect_same_maps(m, uncached(normalized));
}

TEST_F(MapCacheTest, ChangingAReferencedFileRecomputesTheMapThatReadsIt) {
  MapEvaluationReport first, second;
  evaluate(five_maps(), first);
  write_weight_ply(dir_.path / "weight.ply", surface_, 3.0);
  const EvaluatedMaps m = evaluate(five_maps(), second);
  EXPECT_EQ(second.computed, (Names{"painted"}));
  EXPECT_EQ(second.from_cache.size(), 4u);
  for (int v = 0; v < surface_.input.vertex_count(); ++v)
    EXPECT_NEAR(m.scalar.at("painted")[surface_.input_to_intrinsic[v]], 3.0 * surface_.input.positions[static_cast<size_t>(v)].x() + 1.0, 1e-6);
}

TEST_F(MapCacheTest, ChangingTheRefinementRecomputesEveryMap) {
  MapEvaluationReport first, refined_report, again;
  evaluate(five_maps(), first);
  const SurfaceSpec refined_spec{"shape:square", std::nullopt, 0.015, 0.0};  // the grid's faces: 0.022
  const PreparedSurface refined = prepare_surface(refined_spec);
  ASSERT_GT(refined.domain.vertex_count, surface_.domain.vertex_count);
  const EvaluatedMaps m = evaluate(five_maps(), refined_report, &refined, &refined_spec);
  EXPECT_EQ(refined_report.computed.size(), 5u);
  EXPECT_TRUE(refined_report.notes.empty()) << "other keys, not the same entries refused: " << refined_report.notes.front();
  EXPECT_TRUE(refined_report.from_cache.empty());
  EXPECT_EQ(m.scalar.at("ramp").size(), static_cast<size_t>(refined.domain.vertex_count));
  expect_same_maps(m, uncached(five_maps(), &refined));
  // Both surfaces' entries live side by side.
  evaluate(five_maps(), again);
  EXPECT_EQ(again.from_cache.size(), 5u);
  EXPECT_EQ(entries(), 10u);
}

TEST_F(MapCacheTest, ACorruptOrTruncatedEntryIsIgnoredRecomputedAndRewritten) {
  MapEvaluationReport first, second, third;
  evaluate(five_maps(), first);
  const fs::path ramp = entry_of(five_maps(), "ramp"), east = entry_of(five_maps(), "east");
  fs::resize_file(ramp, fs::file_size(ramp) / 2);
  {
    std::fstream f(east, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(east)) - 20);
    f.put('\x7f');
  }
  const EvaluatedMaps m = evaluate(five_maps(), second);
  // (Reports list maps in dependency order, names sorted where free: east before ramp.)
  EXPECT_EQ(second.computed, (Names{"east", "ramp"}));
  ASSERT_EQ(second.notes.size(), 2u);
  EXPECT_NE(second.notes[0].find("checksum"), std::string::npos) << second.notes[0];
  EXPECT_NE(second.notes[1].find("truncated"), std::string::npos) << second.notes[1];
  expect_same_maps(m, uncached(five_maps()));
  evaluate(five_maps(), third);
  EXPECT_EQ(third.from_cache.size(), 5u);
  EXPECT_TRUE(third.notes.empty());
}

TEST_F(MapCacheTest, AnEntryIsUsedOnlyForItsOwnKeyKindAndCount) {
  const MapCacheKey a = MapCacheKey::of("{\"a\":1}"), b = MapCacheKey::of("{\"b\":2}");
  ASSERT_EQ(cache_.store_scalar(a, IntrinsicVertexData<double>{1.0, 2.0, 3.0, 4.0, 5.0}), "");
  const auto hit = cache_.load_scalar(a, 5);
  ASSERT_TRUE(hit.values.has_value());
  EXPECT_EQ(*hit.values, (IntrinsicVertexData<double>{1.0, 2.0, 3.0, 4.0, 5.0}));
  const auto wrong_count = cache_.load_scalar(a, 6);
  EXPECT_FALSE(wrong_count.values.has_value());
  EXPECT_NE(wrong_count.rejected.find("holds 5 values for 6 intrinsic vertices"), std::string::npos) << wrong_count.rejected;
  const auto wrong_kind = cache_.load_vector(a, 5);
  EXPECT_FALSE(wrong_kind.values.has_value());
  EXPECT_NE(wrong_kind.rejected.find("other kind"), std::string::npos) << wrong_kind.rejected;
  // Another key's file name with this entry in it (what a hash collision would look like).
  fs::copy_file(cache_.entry_path(a), cache_.entry_path(b));
  const auto collision = cache_.load_scalar(b, 5);
  EXPECT_FALSE(collision.values.has_value());
  EXPECT_NE(collision.rejected.find("key differs"), std::string::npos) << collision.rejected;
  // No entry at all: a plain miss, nothing to report.
  const auto absent = cache_.load_scalar(MapCacheKey::of("{}"), 5);
  EXPECT_FALSE(absent.values.has_value());
  EXPECT_EQ(absent.rejected, "");
}

TEST_F(MapCacheTest, TheFolderKeepsToItsBudgetDroppingTheLeastRecentlyUsed) {
  const IntrinsicVertexData<double> values(1000, 0.5);
  const MapCache probe(cache_dir_.path / "probe");
  ASSERT_EQ(probe.store_scalar(MapCacheKey::of("size"), values), "");
  const std::uintmax_t entry_bytes = fs::file_size(probe.entry_path(MapCacheKey::of("size")));
  const MapCache small(cache_dir_.path / "small", 3 * entry_bytes + entry_bytes / 2);  // room for three
  std::vector<MapCacheKey> keys;
  for (int i = 0; i < 6; ++i) {
    keys.push_back(MapCacheKey::of("{\"i\":" + std::to_string(i) + "}"));
    ASSERT_EQ(small.store_scalar(keys.back(), values), "");
    // Entries written within one clock tick would tie: space them.
    fs::last_write_time(small.entry_path(keys.back()), fs::file_time_type::clock::now() - std::chrono::seconds(60 - i));
  }
  std::uintmax_t total = 0;
  for (const auto& e : fs::directory_iterator(cache_dir_.path / "small" / "maps")) total += e.file_size();
  EXPECT_LE(total, 3 * entry_bytes + entry_bytes / 2);
  EXPECT_TRUE(fs::exists(small.entry_path(keys[5])));
  EXPECT_FALSE(fs::exists(small.entry_path(keys[0])));
  EXPECT_FALSE(fs::exists(small.entry_path(keys[1])));
}

TEST(MapCacheEnvironment, NoCacheTurnsItOffAndTheFolderFollowsTheVariables) {
  {
    const ScopedEnv off("PHYSARUM_NO_CACHE", "1"), dir("PHYSARUM_CACHE_DIR", "/tmp/somewhere");
    EXPECT_FALSE(MapCache::from_environment().enabled());
  }
  {
    const ScopedEnv on("PHYSARUM_NO_CACHE", "0"), dir("PHYSARUM_CACHE_DIR", "/tmp/somewhere");
    const MapCache cache = MapCache::from_environment();
    EXPECT_TRUE(cache.enabled());
    EXPECT_EQ(cache.folder(), fs::path("/tmp/somewhere"));
  }
  {
    const ScopedEnv on("PHYSARUM_NO_CACHE", nullptr), dir("PHYSARUM_CACHE_DIR", nullptr), xdg("XDG_CACHE_HOME", "/tmp/xdg");
    EXPECT_EQ(MapCache::from_environment().folder(), fs::path("/tmp/xdg/physarum"));
  }
  {
    const ScopedEnv on("PHYSARUM_NO_CACHE", nullptr), dir("PHYSARUM_CACHE_DIR", nullptr), xdg("XDG_CACHE_HOME", nullptr),
        home("HOME", "/tmp/home");
    EXPECT_EQ(MapCache::from_environment().folder(), fs::path("/tmp/home/.cache/physarum"));
  }
  {
    const ScopedEnv on("PHYSARUM_NO_CACHE", nullptr), dir("PHYSARUM_CACHE_DIR", "off");
    EXPECT_FALSE(MapCache::from_environment().enabled());
  }
  {
    const ScopedEnv limit("PHYSARUM_CACHE_MAX_MB", "lots");
    EXPECT_THROW(MapCache::from_environment(), UsageError);
  }
}

TEST_F(MapCacheTest, ADisabledCacheComputesEverythingAndWritesNothing) {
  const ScopedEnv off("PHYSARUM_NO_CACHE", "1"), dir("PHYSARUM_CACHE_DIR", cache_dir_.path.c_str());
  const MapCache disabled = MapCache::from_environment();
  const json maps = five_maps();
  const MapSet set = parse_maps(maps, dir_.path.string(), "scene.json");
  for (int round = 0; round < 2; ++round) {
    MapEvaluationReport report;
    cached_evaluate_maps(MapSources{set, maps, dir_.path.string(), spec_, "scene.json"}, surface_, disabled, &report);
    EXPECT_EQ(report.computed.size(), 5u);
    EXPECT_TRUE(report.from_cache.empty());
    EXPECT_NE(report.summary().find("cache off"), std::string::npos);
  }
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
}  // namespace physarum
