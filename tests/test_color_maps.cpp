// Colour maps: the built-in maps against matplotlib's published colours, stops and their
// validation, the reparameterisation (levels, gamma, remap) against hand-computed values, colour-map
// files and the scene key, the image-assisted (ISOMAP) maps on exemplars whose answer is known, and
// `physarum color_map` / `physarum run` as a user runs them.
#include "common/color/color_map_json.hpp"
#include "common/color/color_mapping.hpp"
#include "common/color/color_map.hpp"
#include "common/output/color_map_strip.hpp"
#include "common/base/errors.hpp"
#include "common/color/isomap_color_map.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/preview_image.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_keys.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace physarum::testing {
namespace {

namespace fs = std::filesystem;

// Expects `call` to throw InputError whose message contains every one of `parts`.
template <typename Call>
void expect_input_error(Call call, std::initializer_list<std::string> parts) {
  try {
    call();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const std::string& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what() << "\n  lacks: " << part;
  }
}

// Relative luminance Y of an sRGB colour (IEC 61966-2-1 decoding, Rec. 709 weights), written out
// here independently of the library's CIELAB code.
double luminance(const SrgbColor& c) {
  double y = 0.0;
  const double weights[3] = {0.2126, 0.7152, 0.0722};
  for (int i = 0; i < 3; ++i) y += weights[i] * (c[i] <= 0.04045 ? c[i] / 12.92 : std::pow((c[i] + 0.055) / 1.055, 2.4));
  return y;
}

double rgb_distance(const SrgbColor& a, const SrgbColor& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double delta_e(const SrgbColor& a, const SrgbColor& b) {
  const auto la = srgb_to_lab(a), lb = srgb_to_lab(b);
  return std::sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) + (la[2] - lb[2]) * (la[2] - lb[2]));
}

SrgbColor hex(std::uint32_t h) { return {((h >> 16) & 0xFF) / 255.0, ((h >> 8) & 0xFF) / 255.0, (h & 0xFF) / 255.0}; }

// ---- named maps ------------------------------------------------------------------------------------

TEST(NamedColorMaps, EndpointsAreMatplotlibsPublishedColours) {
  // matplotlib's tables: viridis #440154 .. #FDE725, magma #000004 .. #FCFDBF, inferno #000004 .. #FCFFA4.
  EXPECT_EQ(ColorMap::named("viridis").sample8(0.0), (Rgb8{0x44, 0x01, 0x54}));
  EXPECT_EQ(ColorMap::named("viridis").sample8(1.0), (Rgb8{0xFD, 0xE7, 0x25}));
  EXPECT_EQ(ColorMap::named("magma").sample8(0.0), (Rgb8{0x00, 0x00, 0x04}));
  EXPECT_EQ(ColorMap::named("magma").sample8(1.0), (Rgb8{0xFC, 0xFD, 0xBF}));
  EXPECT_EQ(ColorMap::named("inferno").sample8(0.0), (Rgb8{0x00, 0x00, 0x04}));
  EXPECT_EQ(ColorMap::named("inferno").sample8(1.0), (Rgb8{0xFC, 0xFF, 0xA4}));
  // inferno's middle entry (128 of 256) is #BC3754 in matplotlib's table.
  EXPECT_EQ(ColorMap::named("inferno").sample8(0.5), (Rgb8{0xBC, 0x37, 0x54}));
}

TEST(NamedColorMaps, PerceptualMapsRiseInLuminance) {
  for (const char* name : {"viridis", "magma", "inferno"}) {
    const ColorMap map = ColorMap::named(name);
    double previous = -1.0;
    for (int k = 0; k <= 200; ++k) {
      const double y = luminance(map.sample(k / 200.0));
      ASSERT_GT(y, previous) << name << " at t = " << k / 200.0;
      previous = y;
    }
  }
}

TEST(NamedColorMaps, GreyIsLinearInSrgb) {
  const ColorMap grey = ColorMap::named("grey");
  for (int k = 0; k <= 20; ++k) {
    const double t = k / 20.0;
    for (double c : grey.sample(t)) EXPECT_NEAR(c, t, 1e-12);
  }
  EXPECT_EQ(grey.sample8(0.5), (Rgb8{128, 128, 128}));  // 127.5 rounds up
}

TEST(NamedColorMaps, EveryNameBuildsAndUnknownNamesAreListed) {
  for (const std::string& name : ColorMap::names()) {
    const ColorMap map = ColorMap::named(name);
    EXPECT_EQ(map.name(), name);
    EXPECT_EQ(map.stops().front().position, 0.0) << name;
    EXPECT_EQ(map.stops().back().position, 1.0) << name;
  }
  expect_input_error([] { ColorMap::named("viridian"); }, {"viridian", "viridis", "lichen"});
}

// ---- stops -----------------------------------------------------------------------------------------

TEST(ColorMapStops, InterpolatesInSrgbAndClamps) {
  const ColorMap map("test", {{0.0, {0, 0, 0}}, {0.5, {1, 0, 0}}, {0.5, {0, 0, 1}}, {1.0, {0, 1, 1}}});
  // Linear in the stored sRGB values (linear light would give 0.5^(1/2.4)-ish values instead).
  EXPECT_NEAR(map.sample(0.25)[0], 0.5, 1e-12);
  // Two stops at one position: a sharp edge, the later colour from the position on.
  EXPECT_NEAR(map.sample(0.4999)[0], 0.9998, 1e-9);
  EXPECT_EQ(map.sample(0.5), (SrgbColor{0, 0, 1}));
  EXPECT_NEAR(map.sample(0.75)[1], 0.5, 1e-12);
  EXPECT_EQ(map.sample(-3.0), (SrgbColor{0, 0, 0}));
  EXPECT_EQ(map.sample(std::nan("")), (SrgbColor{0, 0, 0}));
  EXPECT_EQ(map.sample(9.0), (SrgbColor{0, 1, 1}));
}

TEST(ColorMapStops, RejectsBadStops) {
  expect_input_error([] { ColorMap("one", {{0.0, {0, 0, 0}}}); }, {"'one'", "at least 2 stops"});
  expect_input_error([] { ColorMap("unsorted", {{0.0, {0, 0, 0}}, {0.7, {1, 1, 1}}, {0.3, {1, 0, 0}}}); },
                     {"stop 2", "sorted"});
  expect_input_error([] { ColorMap("outside", {{0.0, {0, 0, 0}}, {1.5, {1, 1, 1}}}); }, {"stop 1", "outside [0, 1]"});
  expect_input_error([] { ColorMap("colour", {{0.0, {0, 0, 0}}, {1.0, {1, 2, 1}}}); }, {"colour component"});
}

// ---- reparameterisation ----------------------------------------------------------------------------

TEST(ColorMapping, LevelsGammaAndRemapMatchHandComputedValues) {
  ColorMapping m;
  m.map = ColorMap::named("grey");  // colour = t: the lookup shows t itself
  m.low = 1.0;
  m.high = 3.0;
  EXPECT_NEAR(m.normalise(2.0, 3.0), 0.5, 1e-12);  // levels: (2 - 1) / (3 - 1)
  EXPECT_EQ(m.normalise(0.0, 3.0), 0.0);           // clamped below
  EXPECT_EQ(m.normalise(7.0, 3.0), 1.0);           // and above
  m.low = 0.0;
  m.high = 1.0;
  m.gamma = 2.0;
  EXPECT_NEAR(m.normalise(0.5, 1.0), 0.25, 1e-12);  // 0.5^2
  EXPECT_NEAR(m.color_float(0.5, 1.0)[0], 0.25, 1e-12);
  m.gamma = 1.0;
  m.remap = RemapCurve({{0, 0}, {0.5, 1}, {1, 0}});
  EXPECT_NEAR(m.normalise(0.25, 1.0), 0.5, 1e-12);  // rising half: 0.25 -> 0.5
  EXPECT_NEAR(m.normalise(0.5, 1.0), 1.0, 1e-12);   // the peak
  EXPECT_NEAR(m.normalise(0.75, 1.0), 0.5, 1e-12);  // falling half: a ring, not a spot
  EXPECT_NEAR(m.normalise(1.0, 1.0), 0.0, 1e-12);
  // Order: levels, then gamma, then remap. Value 1 of 0..2 -> 0.5 -> 0.25 -> remap 0.5 (remap first
  // would give 0.5 -> 1 -> 1).
  m.high = 2.0;
  m.gamma = 2.0;
  EXPECT_NEAR(m.normalise(1.0, 2.0), 0.5, 1e-12);
}

TEST(ColorMapping, RemapCurveClampsOutsideItsPointsAndRejectsBadPoints) {
  const RemapCurve curve({{0.2, 0.9}, {0.8, 0.1}});
  EXPECT_EQ(curve(0.0), 0.9);
  EXPECT_EQ(curve(1.0), 0.1);
  EXPECT_NEAR(curve(0.5), 0.5, 1e-12);
  EXPECT_TRUE(RemapCurve().identity());
  EXPECT_EQ(RemapCurve()(0.3), 0.3);
  expect_input_error([] { RemapCurve({{0, 0}}, "where"); }, {"where", "at least 2 points"});
  expect_input_error([] { RemapCurve({{0, 0}, {0.5, 1}, {0.5, 0}}, "where"); }, {"point 2", "increase strictly"});
  expect_input_error([] { RemapCurve({{0, 0}, {1, 1.5}}, "where"); }, {"point 1", "y = 1.5"});
}

// ---- colour-map files and the scene key ------------------------------------------------------------

TEST(ColorMapJson, RoundTripKeepsMapAndReparameterisation) {
  TempDir dir;
  ColorMapSettings s;
  s.map = ColorMap("mine", {{0.0, hex(0x102030)}, {0.25, hex(0xFF8000)}, {1.0, hex(0xF0E0D0)}});
  s.gamma = 1.5;
  s.remap = RemapCurve({{0, 0}, {0.5, 1}, {1, 0}});
  s.levels = {0.5, 3.0};
  const std::string path = (dir.path / "mine.json").string();
  write_color_map_file(path, s);
  const ColorMapSettings back = read_color_map_file(path);
  EXPECT_EQ(back.map.name(), "mine");
  ASSERT_EQ(back.map.stops().size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.map.stops()[i].position, s.map.stops()[i].position);
    EXPECT_EQ(to_rgb8(back.map.stops()[i].color), to_rgb8(s.map.stops()[i].color));
  }
  EXPECT_EQ(back.gamma, 1.5);
  EXPECT_EQ(back.remap.points(), s.remap.points());
  EXPECT_EQ(back.levels, s.levels);
  // The levels are multiples of U.
  const ColorMapping m = back.mapping(2.0);
  EXPECT_EQ(m.low, 1.0);
  EXPECT_EQ(*m.high, 6.0);
}

TEST(ColorMapJson, AcceptsFloatStopsAndNamedMapsWithSettings) {
  const ColorMapSettings a = color_map_settings_from_json(
      nlohmann::json::parse(R"({"stops": [[0, 0, 0, 0], [1, 1, 0.5, 0.25]]})"), "inline");
  EXPECT_EQ(a.map.sample(1.0), (SrgbColor{1, 0.5, 0.25}));
  const ColorMapSettings b = color_map_settings_from_json(nlohmann::json::parse(R"({"name": "magma", "gamma": 3})"), "inline");
  EXPECT_EQ(b.map.sample8(1.0), (Rgb8{0xFC, 0xFD, 0xBF}));
  EXPECT_EQ(b.gamma, 3.0);
}

TEST(ColorMapJson, EachBadInputIsAnErrorNamingTheFileAndTheProblem) {
  TempDir dir;
  int n = 0;
  auto check = [&](const std::string& text, std::initializer_list<std::string> parts) {
    const std::string path = (dir.path / ("bad" + std::to_string(n++) + ".json")).string();
    std::ofstream(path) << text;
    std::vector<std::string> all(parts);
    all.push_back(path);
    try {
      read_color_map_file(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      for (const std::string& part : all) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what() << "\n  lacks: " << part;
    }
  };
  check(R"({"name": "nope"})", {"unknown colour map 'nope'"});
  check(R"({"stops": [[0, "#000000"], [0.8, "#ffffff"], [0.5, "#ff0000"]]})", {"stop 2", "sorted"});
  check(R"({"stops": [[0, "#000000"], [1.2, "#ffffff"]]})", {"stop 1", "outside [0, 1]"});
  check(R"({"stops": [[-0.1, "#000000"], [1, "#ffffff"]]})", {"stop 0", "outside [0, 1]"});
  check(R"({"stops": [[0, "#000000"]]})", {"at least 2 stops"});
  check(R"({"stops": [[0, "#00000"], [1, "#ffffff"]]})", {"\"#00000\"", "#rrggbb"});
  check(R"({"stops": [[0, "#gg0000"], [1, "#ffffff"]]})", {"\"#gg0000\""});
  check(R"({"stops": [[0, 0, 0, 2], [1, 1, 1, 1]]})", {"stop 0", "colour component"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"]], "gamma": 0})", {"'gamma'", "> 0"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"]], "gamma": -2})", {"'gamma'", "> 0"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"]], "levels": [2, 1]})", {"'levels'", "low < high"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"]], "remap": [[0.5, 0], [0.2, 1]]})", {"'remap'", "point 1"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"]], "stop": 1})", {"unknown key 'stop'"});
  check(R"({"stops": [[0, "#000000"], [1, "#ffffff"])", {"malformed JSON"});
  expect_input_error([&] { read_color_map_file((dir.path / "absent.json").string()); }, {"absent.json", "cannot open"});
}

// A minimal valid scene with `color_map` set to the given JSON value.
std::string scene_with_color_map(const std::string& value) {
  return R"({"mesh": "shape:square", "agents": 10, "time_step": 0.01, "sensor_distance": 0.05, "sensor_angle": 22.5,
  "move_rate": 0.5, "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0,
  "diffuse_rate": 0.0002, "mean_lifetime": 1.0, "activation_time": 0.2, "colormap": )" +
         value + "}";
}

TEST(SceneColorMapKey, NamePathAndInlineObject) {
  TempDir dir;
  fs::create_directories(dir.path / "maps");
  std::ofstream(dir.path / "maps" / "red.json") << R"({"stops": [[0, "#000000"], [1, "#ff0000"]], "gamma": 2})";
  auto load = [&](const std::string& value) {
    const fs::path path = dir.path / "scene.json";
    std::ofstream(path) << scene_with_color_map(value);
    return load_scene(path.string());
  };
  EXPECT_EQ(load(R"("inferno")").color_map.map.name(), "inferno");
  const Scene from_file = load(R"("maps/red.json")");  // relative to the scene's folder
  EXPECT_EQ(from_file.color_map.map.sample8(1.0), (Rgb8{255, 0, 0}));
  EXPECT_EQ(from_file.color_map.gamma, 2.0);
  EXPECT_EQ(load(R"({"name": "ocean", "levels": [0, 1]})").color_map.levels, (std::array<double, 2>{0.0, 1.0}));
  // Absent: viridis over 0 .. 2U.
  TempDir plain;
  std::string text = scene_with_color_map("0");
  text = text.substr(0, text.find(", \"colormap\"")) + "}";
  std::ofstream(plain.path / "scene.json") << text;
  const Scene defaults = load_scene((plain.path / "scene.json").string());
  EXPECT_EQ(defaults.color_map.map.name(), "viridis");
  EXPECT_EQ(defaults.color_map.levels, (std::array<double, 2>{0.0, 2.0}));

  // The key's documentation (README table) lists every built-in map.
  ASSERT_NE(find_scene_key("colormap"), nullptr);
  for (const std::string& name : ColorMap::names())
    EXPECT_NE(find_scene_key("colormap")->allowed_text.find(name), std::string_view::npos) << name;

  const std::string scene = (dir.path / "scene.json").string();
  expect_input_error([&] { load(R"("virdis")"); }, {scene, "'colormap'", "virdis", "viridis"});
  expect_input_error([&] { load(R"("maps/absent.json")"); }, {scene, "'colormap'", "file not found"});
  expect_input_error([&] { load("3"); }, {scene, "'colormap'", "wrong type"});
  expect_input_error([&] { load(R"({"stops": [[0, "#000000"]]})"); }, {scene, "'colormap'", "at least 2 stops"});
}

// ---- image-assisted colour maps (ISOMAP) -----------------------------------------------------------

// A ramp through five distinct colours, piecewise linear in sRGB.
const std::vector<SrgbColor> kRamp = {hex(0x1B1F5E), hex(0x1F8A8A), hex(0x6CC24A), hex(0xF2D22E), hex(0xFAF3E6)};

SrgbColor ramp(double u) {
  const double x = std::clamp(u, 0.0, 1.0) * (kRamp.size() - 1);
  const size_t i = std::min<size_t>(static_cast<size_t>(x), kRamp.size() - 2);
  const double f = x - i;
  SrgbColor c{};
  for (int ch = 0; ch < 3; ++ch) c[ch] = std::round(((1 - f) * kRamp[i][ch] + f * kRamp[i + 1][ch]) * 255.0) / 255.0;
  return c;
}

// A W x W exemplar of ramp colours at random parameters scattered over the pixels; the border band
// (one pixel wide) holds parameters from `border_range` only, so that end of the ramp is background.
ExemplarPixels ramp_exemplar(int w, std::pair<double, double> border_range, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> any(0.0, 1.0), border(border_range.first, border_range.second);
  ExemplarPixels p;
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      const bool on_border = x == 0 || y == 0 || x == w - 1 || y == w - 1;
      p.colors.push_back(ramp(on_border ? border(random) : any(random)));
      p.on_border.push_back(on_border);
    }
  return p;
}

// The ramp parameter of the ramp colour nearest to `c` in CIELAB, and the Delta-E to it.
std::pair<double, double> nearest_on_ramp(const SrgbColor& c) {
  double best_u = 0.0, best = 1e300;
  for (int k = 0; k <= 4000; ++k) {
    const double u = k / 4000.0;
    SrgbColor r{};
    const double x = u * (kRamp.size() - 1);
    const size_t i = std::min<size_t>(static_cast<size_t>(x), kRamp.size() - 2);
    for (int ch = 0; ch < 3; ++ch) r[ch] = (1 - (x - i)) * kRamp[i][ch] + (x - i) * kRamp[i + 1][ch];
    const double d = delta_e(c, r);
    if (d < best) best = d, best_u = u;
  }
  return {best_u, best};
}

// The recovered map runs along the ramp, in order, from the background end: every sample within
// Delta-E 2.3 of the ramp (about one just-noticeable difference; measured: 1.4 at worst, where the
// smoothing spline rounds the ramp's corners), the nearest ramp parameter never going back by more
// than 0.01, and each end within Delta-E 1 of the ramp's end colours.
void expect_recovers_ramp(const ColorMap& map, bool reversed) {
  double previous = -1.0, worst = 0.0;
  for (int k = 0; k <= 255; ++k) {
    auto [u, error] = nearest_on_ramp(map.sample(k / 255.0));
    if (reversed) u = 1.0 - u;
    worst = std::max(worst, error);
    EXPECT_GE(u, previous - 0.01) << "sample " << k << " goes back along the ramp";
    previous = std::max(previous, u);
  }
  EXPECT_LT(worst, 2.3) << "largest Delta-E from the ramp";
  EXPECT_LT(delta_e(map.sample(0.0), reversed ? kRamp.back() : kRamp.front()), 1.0);
  EXPECT_LT(delta_e(map.sample(1.0), reversed ? kRamp.front() : kRamp.back()), 1.0);
}

TEST(IsomapColorMap, RecoversAShuffledRampInOrderFromTheBackgroundEnd) {
  const IsomapColorMap low = isomap_color_map(ramp_exemplar(72, {0.0, 0.04}, 5), "ramp", "test");
  EXPECT_EQ(low.map.stops().size(), 256u);
  expect_recovers_ramp(low.map, false);
  // The same ramp with the other end on the border comes out reversed.
  const IsomapColorMap high = isomap_color_map(ramp_exemplar(72, {0.96, 1.0}, 6), "ramp", "test");
  expect_recovers_ramp(high.map, true);
}

// Two stretches of the ramp with a gap between them: each is a piece of the neighbour graph on its
// own (far more than k nodes each), so only the joining edge makes the geodesics finite. The gap's
// ends are the closest colours of the two pieces, so the join is where the ramp continues, and the
// map must run in order from one end to the other. (With a wide gap the colours alone cannot say
// which ends belong together: the shortest join may attach the far end, and the second piece comes
// out reversed.)
TEST(IsomapColorMap, JoinsSeparatePiecesOfTheGraph) {
  ExemplarPixels p = ramp_exemplar(64, {0.0, 0.04}, 8);
  std::mt19937 random(8);
  std::uniform_real_distribution<double> any(0.0, 1.0);
  for (size_t i = 0; i < p.colors.size(); ++i)
    if (!p.on_border[i]) {
      const double u = any(random);
      p.colors[i] = ramp(u < 0.5 ? 0.4 * u / 0.5 : 0.6 + 0.4 * (u - 0.5) / 0.5);  // [0, 0.4] and [0.6, 1]
    }
  const ColorMap map = isomap_color_map(p, "gap", "test").map;
  double previous = -1.0;
  for (int k = 0; k <= 255; ++k) {
    const SrgbColor c = map.sample(k / 255.0);
    for (double v : c) ASSERT_TRUE(std::isfinite(v));
    const double u = nearest_on_ramp(c).first;
    EXPECT_GE(u, previous - 0.02) << "sample " << k;
    previous = std::max(previous, u);
  }
  EXPECT_LT(delta_e(map.sample(0.0), kRamp.front()), 1.0);
  EXPECT_LT(delta_e(map.sample(1.0), kRamp.back()), 1.0);
}

TEST(IsomapColorMap, TwoColoursGiveTheSegmentBetweenThem) {
  const SrgbColor cream = hex(0xEDE3C8), rust = hex(0xA8461C);
  std::mt19937 random(9);
  ExemplarPixels p;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      const bool on_border = x == 0 || y == 0 || x == 39 || y == 39;
      // Cream dominates the border (background); inside the two are mixed 50/50.
      const bool is_rust = on_border ? random() % 10 == 0 : random() % 2 == 0;
      p.colors.push_back(is_rust ? rust : cream);
      p.on_border.push_back(on_border);
    }
  const ColorMap map = isomap_color_map(p, "two", "test").map;
  EXPECT_LT(rgb_distance(map.sample(0.0), cream), 1e-6);
  EXPECT_LT(rgb_distance(map.sample(1.0), rust), 1e-6);
  for (int k = 0; k <= 255; ++k) {
    // Distance from the segment cream-rust, and the position along it, rising.
    const SrgbColor c = map.sample(k / 255.0);
    double along = 0.0, length2 = 0.0;
    for (int ch = 0; ch < 3; ++ch) along += (c[ch] - cream[ch]) * (rust[ch] - cream[ch]), length2 += (rust[ch] - cream[ch]) * (rust[ch] - cream[ch]);
    along /= length2;
    SrgbColor foot{};
    for (int ch = 0; ch < 3; ++ch) foot[ch] = cream[ch] + along * (rust[ch] - cream[ch]);
    EXPECT_LT(rgb_distance(c, foot), 1e-6) << "sample " << k;
    EXPECT_NEAR(along, k / 255.0, 1e-6) << "sample " << k;  // evenly along the segment
  }
}

TEST(IsomapColorMap, IsDeterministicAndRejectsOneColour) {
  const ExemplarPixels p = ramp_exemplar(48, {0.0, 0.04}, 2);
  const ColorMap a = isomap_color_map(p, "a", "test").map, b = isomap_color_map(p, "b", "test").map;
  for (size_t i = 0; i < a.stops().size(); ++i) ASSERT_EQ(a.stops()[i].color, b.stops()[i].color);
  ExemplarPixels flat;
  flat.colors.assign(100, hex(0x336699));
  expect_input_error([&] { isomap_color_map(flat, "flat", "flat.png"); }, {"flat.png", "only one colour"});
}

TEST(IsomapColorMap, ShippedExemplarMapIsWhatTheExemplarGives) {
  const fs::path folder = fs::path(PHYSARUM_SOURCE_DIR) / "tools" / "colormaps";
  const ColorMapSettings shipped = read_color_map_file((folder / "lichen_from_exemplar.json").string());
  const IsomapColorMap again = isomap_color_map_from_image((folder / "exemplar_lichen.png").string());
  ASSERT_EQ(shipped.map.stops().size(), again.map.stops().size());
  for (size_t i = 0; i < again.map.stops().size(); ++i)
    ASSERT_EQ(to_rgb8(shipped.map.stops()[i].color), to_rgb8(again.map.stops()[i].color)) << "stop " << i;
  // Background bark (grey-brown) at the low end, the lichen's orange centre at the high end.
  const SrgbColor high = again.map.sample(1.0);
  EXPECT_GT(high[0], high[1]);
  EXPECT_GT(high[1], high[2]);
  EXPECT_LT(delta_e(again.map.sample(0.0), again.background), delta_e(again.map.sample(1.0), again.background));
}

// Every colour-map file shipped in tools/colormaps/ reads without error.
TEST(IsomapColorMap, ShippedColourMapFilesRead) {
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(PHYSARUM_SOURCE_DIR) / "tools" / "colormaps"))
    if (e.path().extension() == ".json") {
      EXPECT_NO_THROW(read_color_map_file(e.path().string())) << e.path();
      ++files;
    }
  EXPECT_GE(files, 2);
  // blue_rings: the ring (blue end) on a spot's flank, brown-ish at its peak, skin at zero.
  const ColorMapping rings = read_color_map_file((fs::path(PHYSARUM_SOURCE_DIR) / "tools" / "colormaps" / "blue_rings.json").string()).mapping(1.0);
  EXPECT_EQ(rings.color(0.55 * 3.0, 3.0), (Rgb8{0x2F, 0x74, 0xE0}));
  EXPECT_EQ(rings.color(0.0, 3.0), (Rgb8{0xD8, 0xB4, 0x6A}));
}

// ---- the command line ------------------------------------------------------------------------------

// Writes a ramp exemplar as a PNG.
void write_ramp_png(const fs::path& path) {
  const ExemplarPixels p = ramp_exemplar(64, {0.0, 0.04}, 4);
  RgbImage image;
  image.width = image.height = 64;
  for (const SrgbColor& c : p.colors)
    for (std::uint8_t v : to_rgb8(c)) image.pixels.push_back(v);
  write_rgb_png(path.string(), image);
}

std::array<int, 3> image_shape(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  if (!in) return {0, 0, 0};
  return {in->spec().width, in->spec().height, in->spec().nchannels};
}

TEST(ColorMapCommand, WritesTheMapAndItsStrip) {
  TempDir dir;
  write_ramp_png(dir.path / "exemplar.png");
  const CommandResult r = run_physarum("colormap " + quoted(dir.path / "exemplar.png") + " --out " + quoted(dir.path / "map.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ColorMapSettings map = read_color_map_file((dir.path / "map.json").string());
  EXPECT_EQ(map.map.stops().size(), 256u);
  expect_recovers_ramp(map.map, false);
  // The strip (default: the map's name with .png): 512 x 64, left end = the map at 0, right = at 1.
  ASSERT_EQ(image_shape(dir.path / "map.png"), (std::array<int, 3>{512, 64, 3}));
  auto in = OIIO::ImageInput::open((dir.path / "map.png").string());
  std::vector<std::uint8_t> pixels(512 * 64 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  EXPECT_EQ((Rgb8{pixels[0], pixels[1], pixels[2]}), map.map.sample8(0.0));
  const size_t last = (63 * 512 + 511) * 3;
  EXPECT_EQ((Rgb8{pixels[last], pixels[last + 1], pixels[last + 2]}), map.map.sample8(1.0));

  // --stops and --strip.
  const CommandResult few = run_physarum("colormap " + quoted(dir.path / "exemplar.png") + " --out " + quoted(dir.path / "few.json") +
                                         " --stops 16 --strip " + quoted(dir.path / "few_strip.png"));
  ASSERT_EQ(few.exit_code, 0) << few.err;
  EXPECT_EQ(read_color_map_file((dir.path / "few.json").string()).map.stops().size(), 16u);
  EXPECT_EQ(image_shape(dir.path / "few_strip.png")[0], 512);
  EXPECT_FALSE(fs::exists(dir.path / "few.png"));
}

TEST(ColorMapCommand, BadImageExitsOneAndLeavesNothing) {
  TempDir dir;
  std::ofstream(dir.path / "not_an_image.png") << "this is text, not a PNG";
  for (const fs::path& image : {dir.path / "absent.png", dir.path / "not_an_image.png"}) {
    const CommandResult r = run_physarum("colormap " + quoted(image) + " --out " + quoted(dir.path / "map.json"));
    EXPECT_EQ(r.exit_code, 1) << image;
    EXPECT_NE(r.err.find(image.string()), std::string::npos) << r.err;
  }
  // Only the text file remains: no map, no strip, no temporaries.
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"not_an_image.png"});
  // A default strip name that would overwrite the exemplar is refused (usage error), the image kept.
  write_ramp_png(dir.path / "lichen.png");
  const auto size = fs::file_size(dir.path / "lichen.png");
  EXPECT_EQ(run_physarum("colormap " + quoted(dir.path / "lichen.png") + " --out " + quoted(dir.path / "lichen.json")).exit_code, 2);
  EXPECT_EQ(fs::file_size(dir.path / "lichen.png"), size);
  EXPECT_FALSE(fs::exists(dir.path / "lichen.json"));
}

// `physarum run` colours pheromone.ply through the scene's map, records it in run.json, and
// `physarum render` without --color_map re-colours the same way.
TEST(ColorMapCommand, RunHonoursTheScenesColorMap) {
  TempDir dir;
  std::ofstream(dir.path / "scene.json") << R"({
  "mesh": "shape:square", "scale_to_area": 1.0, "agents": 1000, "time_step": 0.02,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "seed": 3,
  "colormap": {"stops": [[0, "#102030"], [1, "#f0e0d0"]], "gamma": 2, "levels": [0, 1]}
})";
  const CommandResult r = run_physarum("run " + quoted(dir.path / "scene.json") + " --backend reference --steps 30 --out " +
                                       quoted(dir.path / "run"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream run_json(dir.path / "run" / "run.json");
  const nlohmann::json j = nlohmann::json::parse(run_json);
  const double U = j["U"].get<double>();
  EXPECT_EQ(j["colormap"]["gamma"].get<double>(), 2.0);
  // Expected colour, computed here: t = clamp(v / U)^2, then the blend of the two stops in sRGB.
  auto expected = [&](double v) {
    const double t = std::pow(std::clamp(v / U, 0.0, 1.0), 2.0);
    const int from[3] = {0x10, 0x20, 0x30}, to[3] = {0xF0, 0xE0, 0xD0};
    Rgb8 c{};
    for (int ch = 0; ch < 3; ++ch) c[ch] = static_cast<std::uint8_t>(std::lround(from[ch] + t * (to[ch] - from[ch])));
    return c;
  };
  for (const fs::path& ply : {dir.path / "run" / "pheromone.ply", dir.path / "run" / "render" / "pheromone.ply"}) {
    if (ply.parent_path().filename() == "render") {
      ASSERT_EQ(run_physarum("render " + quoted(dir.path / "run") + " --views 1 --width 64 --height 48").exit_code, 0);
    }
    const PlyFields f = read_ply_fields(ply.string());
    const auto& values = f.property("pheromone");
    int above_u = 0;
    for (size_t v = 0; v < values.size(); ++v) {
      const Rgb8 e = expected(values[v]);
      ASSERT_NEAR(f.property("red")[v], e[0], 1) << ply << " vertex " << v;
      ASSERT_NEAR(f.property("green")[v], e[1], 1) << ply << " vertex " << v;
      ASSERT_NEAR(f.property("blue")[v], e[2], 1) << ply << " vertex " << v;
      above_u += values[v] > U;
    }
    EXPECT_GT(above_u, 0) << "the run should reach the top of the levels somewhere";
  }
  // render --color_map MAP.json: that file's map over its own levels (here the grey ramp over 0 .. 4U).
  std::ofstream(dir.path / "grey.json") << R"({"name": "grey", "levels": [0, 4]})";
  ASSERT_EQ(run_physarum("render " + quoted(dir.path / "run") + " --colormap " + quoted(dir.path / "grey.json") +
                         " --views 1 --width 64 --height 48 --out " + quoted(dir.path / "grey"))
                .exit_code,
            0);
  const PlyFields grey = read_ply_fields((dir.path / "grey" / "pheromone.ply").string());
  for (size_t v = 0; v < grey.property("pheromone").size(); ++v) {
    const double level = std::lround(255.0 * std::clamp(grey.property("pheromone")[v] / (4.0 * U), 0.0, 1.0));
    ASSERT_EQ(grey.property("red")[v], level) << "vertex " << v;
    ASSERT_EQ(grey.property("blue")[v], level) << "vertex " << v;
  }
}

}  // namespace
}  // namespace physarum::testing
