// Named surface maps (common/maps/map_definition, common/maps/map_evaluation): every source gives its known
// answer on a known surface, maps authored on the input mesh (PLY properties, textures) reproduce a
// linear function on spot.obj to interpolation accuracy, vector maps land in each face's frame at
// the right angle and length, and every bad map is refused with a message naming the map.
#include "common/base/errors.hpp"
#include "common/maps/map_definition.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/ply_writer.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/output/texture_bake.hpp"
#include "common/output/texture_image.hpp"
#include "map_tool_meshes.hpp"
#include "ply_formats.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physarum {
namespace {

using nlohmann::json;
using testing::TempDir;

PreparedSurface surface_of(const std::string& mesh, std::optional<double> max_circumradius = std::nullopt,
                        std::optional<double> area = std::nullopt) {
  return prepare_surface(SurfaceSpec{mesh, area, max_circumradius, 0.0});
}

EvaluatedMaps evaluate(const json& maps, const PreparedSurface& surface, const std::string& folder = ".") {
  return evaluate_maps(parse_maps(maps, folder, "scene.json"), surface, "scene.json");
}

// ---- regions and ramps: known values at known points ------------------------------------------------

TEST(Maps, RegionsAndRampsGiveKnownValuesAtKnownPoints) {
  // The unit square, scaled to 4 m^2 (factor 2): regions stay in INPUT coordinates, so the answers
  // below are those of the unit square.
  const PreparedSurface s = surface_of("shape:square", 0.05, 4.0);
  const EvaluatedMaps m = evaluate(
      {{"ball", {{"sphere", {{"center", {0.5, 0.5, 0.0}}, {"radius", 0.25}}}}},
       {"soft", {{"sphere", {{"center", {0.5, 0.5, 0.0}}, {"radius", 0.25}}}, {"falloff", 0.125}}},
       {"left", {{"box", {{"min", {-1.0, -1.0, -1.0}}, {"max", {0.25, 2.0, 1.0}}}}}},
       {"above", {{"half_space", {{"point", {0.0, 0.75, 0.0}}, {"normal", {0.0, 2.0, 0.0}}}}}},
       {"ramp_x", {{"axis", "x"}}}},
      s);
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  int checked_falloff_middle = 0, checked_falloff_quarter = 0;
  for (size_t v = 0; v < p.size(); ++v) {
    const double r = (p[v] - Eigen::Vector3d(0.5, 0.5, 0.0)).norm();
    // Vertices away from the edges (rounding of the barycentrics is ~1e-16).
    if (std::abs(r - 0.25) > 1e-9) {
      EXPECT_EQ(m.scalar_map("ball")[v], r < 0.25 ? 1.0 : 0.0) << v;
    }
    if (r < 0.25 - 1e-9 || r > 0.375 + 1e-9) {
      EXPECT_EQ(m.scalar_map("soft")[v], r < 0.25 ? 1.0 : 0.0) << v;
    }
    // Halfway through the falloff, smoothstep is 1/2.
    if (std::abs(r - 0.3125) < 1e-12) {
      EXPECT_NEAR(m.scalar_map("soft")[v], 0.5, 1e-9);
      ++checked_falloff_middle;
    }
    // A quarter into the falloff (the grid vertex (0.5, 7/32), r = 9/32): 1 - smoothstep(1/4) = 27/32.
    if (std::abs(r - 0.28125) < 1e-12) {
      EXPECT_NEAR(m.scalar_map("soft")[v], 27.0 / 32.0, 1e-9);
      ++checked_falloff_quarter;
    }
    if (r > 0.25 + 1e-9 && r < 0.375 - 1e-9) {
      EXPECT_GT(m.scalar_map("soft")[v], 0.0);
      EXPECT_LT(m.scalar_map("soft")[v], 1.0);
    }
    if (std::abs(p[v].x() - 0.25) > 1e-9) {
      EXPECT_EQ(m.scalar_map("left")[v], p[v].x() < 0.25 ? 1.0 : 0.0) << v;
    }
    if (std::abs(p[v].y() - 0.75) > 1e-9) {
      EXPECT_EQ(m.scalar_map("above")[v], p[v].y() > 0.75 ? 1.0 : 0.0) << v;
    }
    EXPECT_NEAR(m.scalar_map("ramp_x")[v], p[v].x(), 1e-12) << v;  // the unit square's box is [0, 1]
  }
  // Grid vertices lie in the middle of the falloff: (0.5, 0.5 +- 0.3125), (0.5 +- 0.3125, 0.5)
  // (0.1875 = 6/32 is a grid coordinate of the 32-cell square) and the 3-4-5 points
  // (0.5 +- 0.1875, 0.5 +- 0.25), (0.5 +- 0.25, 0.5 +- 0.1875): 12 in all.
  EXPECT_EQ(checked_falloff_middle, 12);
  EXPECT_EQ(checked_falloff_quarter, 4);  // (0.5 +- 9/32, 0.5), (0.5, 0.5 +- 9/32)
}

// Thick segments: 1 within the radius of the nearest segment (the perpendicular distance along it,
// the distance to the end beyond its ends), the smoothstep beyond; a degenerate segment is a ball.
TEST(Maps, SegmentsAreOneWithinTheirRadius) {
  const PreparedSurface s = surface_of("shape:square", 0.05, 4.0);
  const EvaluatedMaps m = evaluate(
      {{"lines", {{"segments", {{"points", {{{0.25, 0.5, 0.0}, {0.75, 0.5, 0.0}}, {{0.1, 0.1, 0.0}, {0.1, 0.1, 0.0}}}},
                                {"radius", 0.1}}},
                  {"falloff", 0.1}}}},
      s);
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  int inside = 0, falloff = 0;
  for (size_t v = 0; v < p.size(); ++v) {
    const double x = std::clamp(p[v].x(), 0.25, 0.75);
    const double d = std::min((p[v] - Eigen::Vector3d(x, 0.5, 0.0)).norm(), (p[v] - Eigen::Vector3d(0.1, 0.1, 0.0)).norm());
    const double t = (d - 0.1) / 0.1;
    const double expected = d <= 0.1 ? 1.0 : d >= 0.2 ? 0.0 : 1.0 - t * t * (3.0 - 2.0 * t);
    EXPECT_NEAR(m.scalar_map("lines")[v], expected, 1e-12) << p[v].transpose();
    inside += d < 0.1;
    falloff += d > 0.1 && d < 0.2;
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(falloff, 20);
}

TEST(Maps, AxisRampOfASphereAveragesOneHalf) {
  // Archimedes' hat-box theorem: a sphere's area is uniform in height, so a y-ramp averages 1/2
  // over it (the icosphere's facets approximate that to the order of their size).
  const PreparedSurface s = surface_of("shape:sphere");
  const EvaluatedMaps m = evaluate({{"ramp", {{"axis", "y"}}}}, s);
  double weighted = 0.0, mass = 0.0;
  for (int v = 0; v < s.domain.vertex_count; ++v)
    weighted += s.domain.vertex_mass[v] * m.scalar_map("ramp")[v], mass += s.domain.vertex_mass[v];
  EXPECT_NEAR(weighted / mass, 0.5, 1e-3);
}

// ---- arithmetic --------------------------------------------------------------------------------------

TEST(Maps, EachArithmeticOperationGivesItsKnownAnswer) {
  const PreparedSurface s = surface_of("shape:square");
  const EvaluatedMaps m = evaluate({{"quarter", 0.25},
                                    {"three", 3.0},
                                    {"ranged", {{"map", "quarter"}, {"range", {2.0, 6.0}}}},
                                    {"inverted", {{"invert", "quarter"}}},
                                    {"below", {{"threshold", "quarter"}, {"at", 0.3}}},
                                    {"at_edge", {{"threshold", "quarter"}, {"at", 0.25}}},
                                    {"clamped", {{"clamp", "three"}, {"min", 0.0}, {"max", 2.0}}},
                                    {"floor_only", {{"clamp", "quarter"}, {"min", 0.5}}},
                                    {"sum", {{"sum", {"quarter", "three", 1.0}}}},
                                    {"product", {{"product", {"quarter", "three", 2.0}}}},
                                    {"smallest", {{"min", {"three", "quarter", 1.0}}}},
                                    {"largest", {{"max", {"quarter", 1.0, "three"}}}}},
                                   s);
  const std::map<std::string, double> expected = {
      {"ranged", 3.0},  {"inverted", 0.75}, {"below", 0.0},  {"at_edge", 1.0},   {"clamped", 2.0},  {"floor_only", 0.5},
      {"sum", 4.25},    {"product", 1.5},   {"smallest", 0.25}, {"largest", 3.0}};
  for (const auto& [name, value] : expected)
    for (int v = 0; v < s.domain.vertex_count; ++v) ASSERT_DOUBLE_EQ(m.scalar_map(name)[v], value) << name;
}

TEST(Maps, MapsMayNameEachOtherInAnyOrder) {
  // "c" reads "b" reads "a", given the other way round.
  const MapSet set = parse_maps({{"c", {{"invert", "b"}}}, {"b", {{"map", "a"}, {"range", {0.0, 0.5}}}}, {"a", 0.5}}, ".", "s");
  std::vector<std::string> order;
  for (const MapDefinition& d : set.in_dependency_order()) order.push_back(d.name);
  EXPECT_EQ(order, (std::vector<std::string>{"a", "b", "c"}));
  const EvaluatedMaps m = evaluate_maps(set, surface_of("shape:square"), "s");
  EXPECT_DOUBLE_EQ(m.scalar_map("c")[0], 0.75);
}

// A map painted elsewhere and saved as ASCII (trimesh, Blender's exporter option) or big-endian PLY
// gives the same values on the surface as the little-endian file physarum writes, so the same run.
TEST(Maps, APlyMapReadsTheSameInEveryPlyFormat) {
  TempDir dir;
  const PreparedSurface square = surface_of("shape:square", 0.05);
  std::vector<float> weight(square.input.positions.size());
  for (size_t v = 0; v < weight.size(); ++v)
    weight[v] = static_cast<float>(square.input.positions[v].x() * square.input.positions[v].x() + 0.1 * square.input.positions[v].y());
  std::vector<IntrinsicVertexData<double>> maps;
  for (const char* format : {"binary_little_endian", "ascii", "binary_big_endian"}) {
    const std::string file = std::string(format) + ".ply";
    testing::write_ply_in_format((dir.path / file).string(), format, square.input, "w", weight);
    maps.push_back(evaluate({{"w", {{"ply", file}, {"property", "w"}}}}, square, dir.path.string()).scalar_map("w"));
  }
  const auto [low, high] = std::minmax_element(maps[0].begin(), maps[0].end());
  EXPECT_GT(*high - *low, 0.1);  // the map is not constant
  EXPECT_EQ(maps[1], maps[0]);
  EXPECT_EQ(maps[2], maps[0]);
}

// ---- refusals ------------------------------------------------------------------------------------------

TEST(Maps, BadMapsAreRefusedNamingTheMap) {
  auto parse_error = [](const json& maps) { return testing::input_error_of([&] { parse_maps(maps, "/nonexistent-folder", "scene.json"); }); };
  struct Case {
    json maps;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases = {
      {{{"a", {{"invert", "b"}}}, {"b", {{"sum", {"c", 1}}}}, {"c", {{"invert", "a"}}}},
       {"key 'maps': map '", "cycle (a -> b -> c -> a)"}},
      {{{"a", {{"invert", "a"}}}}, {"map 'a'", "cycle (a -> a)"}},
      {{{"a", {{"invert", "nope"}}}}, {"map 'a'", "reads map 'nope', which is not defined"}},
      {{{"east", {{"direction", {1, 0, 0}}}}, {"a", {{"invert", "east"}}}}, {"map 'a'", "'east', a vector map"}},
      {{{"a", {{"ply", "missing.ply"}, {"property", "w"}}}}, {"map 'a'", "file not found", "missing.ply"}},
      {{{"a", {{"texture", "missing.png"}, {"channel", "r"}}}}, {"map 'a'", "file not found"}},
      {{{"a", {{"texture", "x.png"}, {"channel", "q"}}}}, {"map 'a'", "\"channel\" = \"q\""}},
      {{{"a", {{"geodesic", {{"from", "b"}}}}}}, {"map 'a'", "no known map source", "\"sphere\""}},
      {{{"a", {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}, {"falloff", -1}}}}, {"map 'a'", "falloff"}},
      {{{"a", {{"sphere", {{"center", {0, 0}}, {"radius", 1}}}}}}, {"map 'a'", "three numbers"}},
      {{{"a", {{"axis", "w"}}}}, {"map 'a'", "\"axis\" = \"w\""}},
      {{{"a", {{"segments", {{"points", json::array()}, {"radius", 0.1}}}}}}, {"map 'a'", "non-empty list of [[x, y, z]"}},
      {{{"a", {{"segments", {{"points", {{{0, 0, 0}}}}, {"radius", 0.1}}}}}}, {"map 'a'", "\"points\"[0]", "must be a pair"}},
      {{{"a", {{"segments", {{"points", {{{0, 0, 0}, {1, 1}}}}, {"radius", 0.1}}}}}}, {"map 'a'", "three numbers"}},
      {{{"a", {{"segments", {{"points", {{{0, 0, 0}, {1, 1, 1}}}}, {"radius", -1}}}}}}, {"map 'a'", "\"radius\" must be >= 0"}},
      {{{"a", {{"map", "b"}}}, {"b", 1}}, {"map 'a'", "missing \"range\""}},
      {{{"a", {{"sum", json::array()}}}}, {"map 'a'", "non-empty list"}},
      {{{"a", {{"clamp", 1}}}}, {"map 'a'", "needs \"min\", \"max\""}},
      {{{"a", {{"invert", 1}, {"extra", 2}}}}, {"map 'a'", "unknown field \"extra\""}},
      {{{"a", {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}, {"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}}},
       {"map 'a'", "two sources"}},
      {{{"red", 1}}, {"map 'red'", "PLY property"}},
      {{{"flow", {{"direction", {1, 0, 0}}}}, {"flow_y", 1}}, {"map 'flow_y'", "component flow_y of the vector map 'flow'"}},
      {{{"a b", 1}}, {"map 'a b'", "letters, digits"}},
      {json::array(), {"key 'maps'", "must be an object"}},
  };
  for (const Case& c : cases) {
    const std::string message = parse_error(c.maps);
    SCOPED_TRACE(c.maps.dump());
    ASSERT_FALSE(message.empty());
    EXPECT_NE(message.find("scene.json: key 'maps'"), std::string::npos) << message;
    for (const std::string& s : c.says) EXPECT_NE(message.find(s), std::string::npos) << message;
  }
}

TEST(Maps, SourcesThatDoNotFitTheSurfaceAreRefused) {
  TempDir dir;
  const PreparedSurface square = surface_of("shape:square");
  // A PLY on another mesh: its vertex count is not the square's.
  const InputMesh sphere = load_mesh("shape:sphere");
  const InputVertexData<double> ones(static_cast<size_t>(sphere.vertex_count()), 1.0);
  write_field_ply((dir.path / "other.ply").string(), sphere, ones, {}, "w");
  std::string message = testing::input_error_of([&] { evaluate({{"w", {{"ply", "other.ply"}, {"property", "w"}}}}, square, dir.path.string()); });
  EXPECT_NE(message.find("map 'w'"), std::string::npos) << message;
  EXPECT_NE(message.find("has 2562 vertices, but the input mesh shape:square has 1089"), std::string::npos) << message;
  // The right mesh, a property it does not have.
  const InputVertexData<double> zeros(static_cast<size_t>(square.input.vertex_count()), 0.0);
  write_field_ply((dir.path / "square.ply").string(), square.input, zeros, {}, "w");
  message = testing::input_error_of([&] { evaluate({{"v", {{"ply", "square.ply"}, {"property", "weight"}}}}, square, dir.path.string()); });
  EXPECT_NE(message.find("map 'v'"), std::string::npos) << message;
  EXPECT_NE(message.find("no vertex property 'weight' (it has: w"), std::string::npos) << message;
  // A face vector the file does not have.
  message = testing::input_error_of([&] { evaluate({{"f", {{"ply", "square.ply"}, {"face_property", "flow"}}}}, square, dir.path.string()); });
  EXPECT_NE(message.find("no face property 'flow_x'"), std::string::npos) << message;
  // A texture on a mesh without UVs.
  {
    auto out = OIIO::ImageOutput::create((dir.path / "grey.png").string());
    OIIO::ImageSpec spec(2, 2, 1, OIIO::TypeDesc::UINT8);
    const unsigned char pixels[4] = {0, 64, 128, 255};
    ASSERT_TRUE(out->open((dir.path / "grey.png").string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels) && out->close());
  }
  message = testing::input_error_of([&] { evaluate({{"t", {{"texture", "grey.png"}, {"channel", "r"}}}}, square, dir.path.string()); });
  EXPECT_NE(message.find("map 't'"), std::string::npos) << message;
  EXPECT_NE(message.find("needs texture coordinates (UVs), and shape:square has none"), std::string::npos) << message;
  // An alpha channel the image does not have (refused before any UV is looked at).
  const InputMesh with_uvs = [&] {
    InputMesh m = square.input;
    for (const auto& p : m.positions) m.uvs.push_back(p.head<2>());
    m.triangle_uvs = m.triangles;
    return m;
  }();
  const PreparedSurface textured = prepare_surface(with_uvs, SurfaceSpec{"square with UVs", std::nullopt, std::nullopt, 0.0});
  message = testing::input_error_of([&] { evaluate({{"t", {{"texture", "grey.png"}, {"channel", "a"}}}}, textured, dir.path.string()); });
  EXPECT_NE(message.find("no alpha"), std::string::npos) << message;
  // A ramp along an axis the flat square has no extent in.
  message = testing::input_error_of([&] { evaluate({{"height", {{"axis", "z"}}}}, square, "."); });
  EXPECT_NE(message.find("map 'height'"), std::string::npos) << message;
  EXPECT_NE(message.find("flat along z"), std::string::npos) << message;
}

// ---- maps painted on the input mesh: spot.obj ------------------------------------------------------------

// f(x) = a . x + b, a linear function of position in input coordinates.
double linear_function(const Eigen::Vector3d& x) { return 0.7 * x.x() - 0.4 * x.y() + 0.25 * x.z() + 1.5; }

TEST(Maps, PlyVertexPropertyReproducesALinearFunctionOnSpot) {
  PHYSARUM_REQUIRE_SHARED_MESH(spot, "spot.obj");
  // Refined, so most intrinsic vertices lie inside input faces (not on input vertices).
  const PreparedSurface s = surface_of(spot, 0.02, 1.0);
  TempDir dir;
  InputVertexData<double> f(static_cast<size_t>(s.input.vertex_count()));
  double largest = 0.0;
  for (int v = 0; v < s.input.vertex_count(); ++v) f[v] = linear_function(s.input.positions[v]), largest = std::max(largest, std::abs(f[v]));
  write_field_ply((dir.path / "linear.ply").string(), s.input, f, {}, "f");
  const EvaluatedMaps m = evaluate({{"f", {{"ply", "linear.ply"}, {"property", "f"}}}}, s, dir.path.string());
  // Each intrinsic vertex lies in one flat input face, where barycentric interpolation of a linear
  // function is exact; what remains is the PLY's float32 storage of the corner values (relative
  // 2^-24, so 6e-8 of the largest |f|) and double rounding: 1e-6 of the largest |f| bounds both.
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  ASSERT_GT(s.domain.vertex_count, s.input.vertex_count());  // the refinement inserted vertices
  double worst = 0.0;
  for (size_t v = 0; v < p.size(); ++v) worst = std::max(worst, std::abs(m.scalar_map("f")[v] - linear_function(p[v])));
  EXPECT_LT(worst, 1e-6 * largest);
}

TEST(Maps, TextureReproducesALinearFunctionOnSpot) {
  PHYSARUM_REQUIRE_SHARED_MESH(spot, "spot.obj");
  const PreparedSurface s = surface_of(spot, 0.005, 1.0);
  const InputMesh& in = s.input;
  ASSERT_FALSE(in.uvs.empty());
  // The texture, rasterised here from spot's UV map: each texel whose centre lies in a UV triangle
  // holds g = (f - low) / (high - low) at the matching 3D point of that input triangle (f linear in
  // position, so g is linear in UV inside each triangle), as a 16-bit PNG.
  constexpr int kSize = 1024;
  double low = 1e300, high = -1e300;
  for (const auto& x : in.positions) low = std::min(low, linear_function(x)), high = std::max(high, linear_function(x));
  auto g = [&](const Eigen::Vector3d& x) { return (linear_function(x) - low) / (high - low); };
  std::vector<std::uint16_t> pixels(kSize * kSize, 0);
  std::vector<int> owner(kSize * kSize, -1);  // the input triangle that wrote each texel
  for (int t = 0; t < in.triangle_count(); ++t) {
    std::array<Eigen::Vector2d, 3> uv;
    for (int c = 0; c < 3; ++c) uv[c] = in.uvs[in.triangle_uvs[t][c]] * kSize;  // texel units, y up
    const Eigen::Vector2d lo = uv[0].cwiseMin(uv[1]).cwiseMin(uv[2]), hi = uv[0].cwiseMax(uv[1]).cwiseMax(uv[2]);
    if (lo.minCoeff() < 0 || hi.maxCoeff() > kSize) continue;  // a triangle in another UV tile: not drawn
    const double area = (uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() - (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x();
    if (area == 0) continue;
    for (int i = static_cast<int>(lo.x()); i <= static_cast<int>(hi.x()) && i < kSize; ++i)
      for (int j = static_cast<int>(lo.y()); j <= static_cast<int>(hi.y()) && j < kSize; ++j) {
        const Eigen::Vector2d c(i + 0.5, j + 0.5);
        auto edge = [&](int k) {
          const Eigen::Vector2d a = uv[(k + 1) % 3] - c, b = uv[(k + 2) % 3] - c;
          return (a.x() * b.y() - a.y() * b.x()) / area;
        };
        const Eigen::Vector3d w(edge(0), edge(1), edge(2));
        if (w.minCoeff() < 0) continue;
        const Eigen::Vector3d x = w[0] * in.positions[in.triangles[t][0]] + w[1] * in.positions[in.triangles[t][1]] +
                                  w[2] * in.positions[in.triangles[t][2]];
        const size_t texel = static_cast<size_t>(kSize - 1 - j) * kSize + static_cast<size_t>(i);  // rows top first
        pixels[texel] = static_cast<std::uint16_t>(std::lround(g(x) * 65535.0));
        owner[texel] = t;
      }
  }
  TempDir dir;
  const std::string png = (dir.path / "linear.png").string();
  {
    auto out = OIIO::ImageOutput::create(png);
    OIIO::ImageSpec spec(kSize, kSize, 1, OIIO::TypeDesc::UINT16);
    ASSERT_TRUE(out->open(png, spec) && out->write_image(OIIO::TypeDesc::UINT16, pixels.data()) && out->close());
  }
  const EvaluatedMaps m = evaluate({{"f", {{"texture", "linear.png"}, {"channel", "luma"}}}}, s, dir.path.string());

  // A vertex whose four bilinear texels were all written by the input triangle it lies in reads g
  // exactly (bilinear interpolation reproduces a linear function), up to the 16-bit quantisation
  // of the texels: 0.5 / 65535 = 7.6e-6. Other vertices (their footprint straddles UV edges, seams
  // or uncovered texels) are not judged here.
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  int exact = 0;
  double worst = 0.0;
  for (int v = 0; v < s.domain.vertex_count; ++v) {
    const SurfacePoint& l = s.domain.vertex_location[v];
    const auto& tu = in.triangle_uvs[static_cast<size_t>(l.face)];
    const Eigen::Vector2d uv = l.barycentric[0] * in.uvs[tu[0]] + l.barycentric[1] * in.uvs[tu[1]] + l.barycentric[2] * in.uvs[tu[2]];
    const double x = uv.x() * kSize - 0.5, y = (1.0 - uv.y()) * kSize - 0.5;
    const int i0 = static_cast<int>(std::floor(x)), j0 = static_cast<int>(std::floor(y));
    if (i0 < 0 || j0 < 0 || i0 + 1 >= kSize || j0 + 1 >= kSize) continue;
    bool own = true;
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj) own = own && owner[static_cast<size_t>(j0 + dj) * kSize + static_cast<size_t>(i0 + di)] == l.face;
    if (!own) continue;
    ++exact;
    worst = std::max(worst, std::abs(m.scalar_map("f")[v] - g(p[static_cast<size_t>(v)])));
  }
  EXPECT_LT(worst, 0.5 / 65535.0 + 1e-7);
  // Enough vertices to mean something (spot's triangles span several texels at 512^2).
  EXPECT_GT(exact, s.domain.vertex_count / 4) << exact << " of " << s.domain.vertex_count;
}

// ---- vector maps ---------------------------------------------------------------------------------------

// The 3D vector (in input units) a face's 2D vector stands for, through the face's own intrinsic
// layout: v = a c1 + b c2 in the layout (corners c0 = 0, c1, c2) is a (P1 - P0) + b (P2 - P0) on the
// input triangle, rescaled from the layout's (scaled) units to input units.
Eigen::Vector3d through_layout(const PreparedSurface& s, int face, const std::array<double, 2>& v, double scale) {
  const auto& c = s.domain.face_corners[static_cast<size_t>(face)];
  Eigen::Matrix2d basis;
  basis << c[1].x(), c[2].x(), c[1].y(), c[2].y();
  const Eigen::Vector2d ab = basis.inverse() * Eigen::Vector2d(v[0], v[1]);
  std::array<Eigen::Vector3d, 3> P;
  for (int k = 0; k < 3; ++k) {
    const SurfacePoint& l = s.domain.vertex_location[s.domain.face_vertices[static_cast<size_t>(face)][k]];
    const auto& t = s.input.triangles[static_cast<size_t>(l.face)];
    P[k] = l.barycentric[0] * s.input.positions[t[0]] + l.barycentric[1] * s.input.positions[t[1]] +
           l.barycentric[2] * s.input.positions[t[2]];
  }
  return (ab[0] * (P[1] - P[0]) + ab[1] * (P[2] - P[0])) * scale;
}

TEST(Maps, DirectionHasTheRightAngleInEachFaceOfTheSquare) {
  // Scaled to 4 m^2 (factor 2): the direction is in input coordinates and keeps its length.
  const PreparedSurface s = surface_of("shape:square", 0.05, 4.0);
  const Eigen::Vector3d d(3.0, 4.0, 0.0);
  const EvaluatedMaps m = evaluate({{"d", {{"direction", {3.0, 4.0, 0.0}}}}}, s);
  const auto& v = m.vector_map("d");
  ASSERT_EQ(static_cast<int>(v.size()), s.domain.face_count);
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  for (int f = 0; f < s.domain.face_count; ++f) {
    // The angle in the face's frame is the direction's angle minus that of the face's first edge
    // (corner 0 to corner 1, read off the corners' input positions; the square is CCW seen from +z).
    const auto& fv = s.domain.face_vertices[static_cast<size_t>(f)];
    const Eigen::Vector3d edge = p[static_cast<size_t>(fv[1])] - p[static_cast<size_t>(fv[0])];
    const double expected = std::atan2(4.0, 3.0) - std::atan2(edge.y(), edge.x());
    const double angle = std::atan2(v[f][1], v[f][0]);
    EXPECT_NEAR(std::remainder(angle - expected, 2 * std::numbers::pi), 0.0, 1e-12) << f;
    EXPECT_NEAR(std::hypot(v[f][0], v[f][1]), 5.0, 1e-12) << f;  // in the plane: the full length, input units
  }
  // Every face, through its own intrinsic layout (an independent route to 3D): d itself.
  for (int f = 0; f < s.domain.face_count; ++f) {
    // The layout is in scaled units (x 2): mapping a vector of input length through it and back to
    // the input triangle divides by 2, which the scale 2 undoes.
    const Eigen::Vector3d back = through_layout(s, f, v[f], 2.0);
    EXPECT_LT((back - d).norm(), 1e-9) << f;
  }
}

// "toward" a point on the flat square: in every face, a unit vector whose angle is that of the
// point seen from the face's centroid (both read off the corners' input positions here); "away_from"
// is its opposite.
TEST(Maps, TowardPointsFromEachFaceToThePoint) {
  const PreparedSurface s = surface_of("shape:square", 0.05, 4.0);
  const Eigen::Vector3d c(0.3, 0.6, 0.0);
  const EvaluatedMaps m = evaluate({{"in", {{"toward", {0.3, 0.6, 0.0}}}}, {"out", {{"away_from", {0.3, 0.6, 0.0}}}}}, s);
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  for (int f = 0; f < s.domain.face_count; ++f) {
    const auto& fv = s.domain.face_vertices[static_cast<size_t>(f)];
    const Eigen::Vector3d centroid = (p[static_cast<size_t>(fv[0])] + p[static_cast<size_t>(fv[1])] + p[static_cast<size_t>(fv[2])]) / 3.0;
    const Eigen::Vector3d edge = p[static_cast<size_t>(fv[1])] - p[static_cast<size_t>(fv[0])];
    const double expected = std::atan2(c.y() - centroid.y(), c.x() - centroid.x()) - std::atan2(edge.y(), edge.x());
    const auto& in = m.vector_map("in")[f];
    const auto& out = m.vector_map("out")[f];
    EXPECT_NEAR(std::remainder(std::atan2(in[1], in[0]) - expected, 2 * std::numbers::pi), 0.0, 1e-9) << f;
    EXPECT_NEAR(std::hypot(in[0], in[1]), 1.0, 1e-12) << f;
    EXPECT_NEAR(in[0] + out[0], 0.0, 1e-12) << f;
    EXPECT_NEAR(in[1] + out[1], 0.0, 1e-12) << f;
  }
}

TEST(Maps, DirectionIsTangentWithItsProjectedLengthOnACurvedSurface) {
  // The icosphere: flat facets meeting at angles. An intrinsic face lying in one facet must carry d
  // projected into that facet's plane: tangent to it and of the projected length (both to rounding).
  const PreparedSurface s = surface_of("shape:sphere", 0.015);
  const Eigen::Vector3d d(1.0, 0.5, -0.25);
  const EvaluatedMaps m = evaluate({{"d", {{"direction", {1.0, 0.5, -0.25}}}}}, s);
  const auto& v = m.vector_map("d");
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  int in_one_facet = 0;
  for (int f = 0; f < s.domain.face_count; ++f) {
    const auto& fv = s.domain.face_vertices[static_cast<size_t>(f)];
    // The facet holding the face, if one does: one of the corners' input faces whose plane holds all
    // three corners.
    std::optional<Eigen::Vector3d> facet_normal;
    for (int k = 0; k < 3 && !facet_normal; ++k) {
      const auto& t = s.input.triangles[static_cast<size_t>(s.domain.vertex_location[fv[k]].face)];
      const Eigen::Vector3d n = (s.input.positions[t[1]] - s.input.positions[t[0]])
                                    .cross(s.input.positions[t[2]] - s.input.positions[t[0]])
                                    .normalized();
      bool holds_all = true;
      for (int c = 0; c < 3; ++c) holds_all = holds_all && std::abs((p[fv[c]] - s.input.positions[t[0]]).dot(n)) < 1e-10;
      if (holds_all) facet_normal = n;
    }
    if (!facet_normal) continue;
    const Eigen::Vector3d n = *facet_normal;
    ++in_one_facet;
    const Eigen::Vector3d back = through_layout(s, f, v[f], 1.0);
    EXPECT_LT(std::abs(back.dot(n)), 1e-9) << f;
    EXPECT_NEAR(std::hypot(v[f][0], v[f][1]), (d - d.dot(n) * n).norm(), 1e-9) << f;
    EXPECT_LT((back - (d - d.dot(n) * n)).norm(), 1e-9) << f;
  }
  // Faces of circumradius <= 0.015 against facets of ~0.04: about a third lie inside one facet.
  EXPECT_GT(in_one_facet, s.domain.face_count / 4);
}

TEST(Maps, PlyFaceVectorIsReadUnderEachFace) {
  // On the flat square a per-face vector field that is the same on every face must come out as
  // that vector's angle in every intrinsic face, whichever input face lies under it; a field that
  // differs per input face must give each intrinsic face the vector of the input face holding its
  // centroid.
  const PreparedSurface s = surface_of("shape:square", 0.02);
  TempDir dir;
  std::vector<double> x(s.input.triangles.size()), y(x.size()), z(x.size(), 0.0);
  for (size_t t = 0; t < x.size(); ++t) {
    // Left half of the square +x, right half +y (the input faces' centroids decide).
    const auto& tri = s.input.triangles[t];
    const double cx = (s.input.positions[tri[0]].x() + s.input.positions[tri[1]].x() + s.input.positions[tri[2]].x()) / 3;
    x[t] = cx < 0.5 ? 1.0 : 0.0;
    y[t] = cx < 0.5 ? 0.0 : 1.0;
  }
  const InputVertexData<double> zeros(static_cast<size_t>(s.input.vertex_count()), 0.0);
  write_fields_ply((dir.path / "flow.ply").string(), s.input, {PlyField{"w", zeros}},
                   {PlyFaceField{"flow_x", x}, PlyFaceField{"flow_y", y}, PlyFaceField{"flow_z", z}}, {}, "test");
  const EvaluatedMaps m = evaluate({{"flow", {{"ply", "flow.ply"}, {"face_property", "flow"}}}}, s, dir.path.string());
  const std::vector<Eigen::Vector3d> p = testing::intrinsic_vertex_positions(s);
  for (int f = 0; f < s.domain.face_count; ++f) {
    const auto& fv = s.domain.face_vertices[static_cast<size_t>(f)];
    const double cx = (p[fv[0]].x() + p[fv[1]].x() + p[fv[2]].x()) / 3;
    if (std::abs(cx - 0.5) < 0.05) continue;  // faces astride the middle line
    const Eigen::Vector3d back = through_layout(s, f, m.vector_map("flow")[f], 1.0);
    const Eigen::Vector3d expected = cx < 0.5 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    EXPECT_LT((back - expected).norm(), 1e-9) << f << " at x " << cx;
  }
}

}  // namespace
}  // namespace physarum
