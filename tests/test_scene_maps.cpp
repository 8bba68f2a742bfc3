// From a scene file to the arrays a backend reads (common/setup/scene_maps): parameters given by maps take
// the maps' values (remapped by their range, in file units), a scene without maps is exactly the
// constant base model, the controls of Sec. 3.3 are the documented sums and conversions, every bad
// reference is refused naming its key, and the command line runs such a scene on both backends and
// writes the maps (`physarum map`, `run --maps-out`) as the values evaluated here.
#include "common/base/errors.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/output/ply_writer.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "test_support.hpp"
#include "api/backend_factory.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

namespace physarum {
namespace {

using nlohmann::json;
using testing::quoted;
using testing::run_physarum;
using testing::TempDir;

// A valid scene on the unit square (every required key), to which a test adds maps and controls.
json base_scene() {
  return {{"mesh", "shape:square"},  {"agents", 200},        {"time_step", 0.02},      {"sensor_distance", 0.05},
          {"sensor_angle", 22.5},    {"move_rate", 0.5},     {"turn_rate", 180.0},     {"turn_frequency", 20.0},
          {"deposit_rate", 1.0},     {"decay_rate", 1.0},    {"diffuse_rate", 0.0002}, {"mean_lifetime", 1.0}};
}

json square_maps() {
  return {{"ramp_x", {{"axis", "x"}}},
          {"ramp_y", {{"axis", "y"}}},
          {"thirty", 30.0},
          {"two", 2.0},
          {"nowhere", {{"sphere", {{"center", {5.0, 5.0, 5.0}}, {"radius", 0.1}}}}},
          {"negative", -1.0},
          {"east", {{"direction", {1.0, 0.0, 0.0}}}}};
}

std::string write_scene(const TempDir& dir, const json& scene, const std::string& name = "scene.json") {
  const std::string path = (dir.path / name).string();
  std::ofstream(path) << scene.dump(2);
  return path;
}


// The message load_scene, or evaluating the loaded scene on its surface, refuses `scene` with.
std::string scene_error(const json& scene) {
  TempDir dir;
  const std::string path = write_scene(dir, scene);
  return testing::input_error_of([&] {
    const Scene s = load_scene(path);
    const PreparedSurface surface = prepare_scene_surface(s);
    scene_arrays(s, surface);
  });
}

TEST(SceneMaps, ASceneWithoutMapsIsExactlyTheConstantModel) {
  TempDir dir;
  const Scene scene = load_scene(write_scene(dir, base_scene()));
  const PreparedSurface surface = prepare_scene_surface(scene);
  const SceneArrays arrays = scene_arrays(scene, surface);
  const VertexParameters constant = VertexParameters::constant(scene.agent_model().parameters, surface.domain.vertex_count);
  for (const ParameterSpec& p : kParameterTable) EXPECT_EQ(arrays.parameters[p.id], constant[p.id]) << p.key;
  EXPECT_TRUE(arrays.controls.read_stimulus.empty());
  EXPECT_TRUE(arrays.controls.write_rate.empty());
  EXPECT_TRUE(arrays.controls.spawn_weight.empty());
  EXPECT_FALSE(arrays.controls.bias.has_value());
  EXPECT_EQ(arrays.controls.spawn_heading, SpawnHeading::Random);
  EXPECT_EQ(arrays.controls.boundary, BoundaryBehaviour::Reflect);
  // A positive constant spawn weight is uniform spawning: the base model too.
  json j = base_scene();
  j["spawn_weight"] = 3.0;
  EXPECT_TRUE(simulation_controls(load_scene(write_scene(dir, j, "w.json")), surface).spawn_weight.empty());
}

TEST(SceneMaps, ParametersTakeTheMapsValuesInFileUnits) {
  TempDir dir;
  json j = base_scene();
  j["maps"] = square_maps();
  j["sensor_distance"] = {{"map", "ramp_x"}, {"range", {0.02, 0.06}}};  // 0.02 + 0.04 x
  j["sensor_angle"] = "thirty";                                        // degrees, as the file's numbers
  j["move_rate"] = {{"map", "ramp_y"}};                                // no range: the map's values (m/s)
  const Scene scene = load_scene(write_scene(dir, j));
  EXPECT_TRUE(std::isnan(scene.agent_model().parameters[Param::sensor_distance]));  // per vertex until evaluated
  const PreparedSurface surface = prepare_scene_surface(scene);
  const VertexParameters p = vertex_parameters(scene, surface);
  for (int v = 0; v < surface.domain.vertex_count; ++v) {
    const int input_vertex = v < surface.input.vertex_count() ? v : -1;
    if (input_vertex < 0) break;  // the unrefined square: every intrinsic vertex is an input vertex
    const Eigen::Vector3d x = surface.input.positions[static_cast<size_t>(input_vertex)];
    EXPECT_NEAR(p[Param::sensor_distance][v], 0.02 + 0.04 * x.x(), 1e-15);
    EXPECT_NEAR(p[Param::sensor_angle][v], 30.0 * std::numbers::pi / 180.0, 1e-15);
    EXPECT_NEAR(p[Param::move_rate][v], x.y(), 1e-15);
    EXPECT_EQ(p[Param::turn_rate][v], scene.agent_model().parameters[Param::turn_rate]);  // the others stay constant
  }
  // The summary value: the square and its grid are symmetric about x = 1/2, so the ramp's
  // mass-weighted mean is exactly 1/2 and sensor_distance's is 0.04.
  const Scene summary = with_mean_parameters(scene, p, surface.domain);
  EXPECT_NEAR(summary.agent_model().parameters[Param::sensor_distance], 0.04, 1e-12);
  EXPECT_NEAR(summary.agent_model().parameters[Param::move_rate], 0.5, 1e-12);
  EXPECT_EQ(summary.agent_model().parameters[Param::decay_rate], scene.agent_model().parameters[Param::decay_rate]);
}

// A mean-lifetime map may reach 0 (a sink, Sec. 3.3), where the hazard is infinite; the constant 0
// stays refused (it would remove every agent every step), as does 0 in a map of any other parameter
// whose range excludes it (decay_rate, in BadReferencesAreRefusedNamingTheKey).
TEST(SceneMaps, AMeanLifetimeMapMayMakeASink) {
  TempDir dir;
  json j = base_scene();
  j["maps"] = square_maps();
  j["mean_lifetime"] = {{"map", "ramp_x"}, {"range", {0.0, 2.0}}};  // 0 on the left edge
  const Scene scene = load_scene(write_scene(dir, j));
  const PreparedSurface surface = prepare_scene_surface(scene);
  const VertexParameters p = vertex_parameters(scene, surface);
  int sinks = 0;
  for (int v = 0; v < surface.domain.vertex_count; ++v) {
    const double x = surface.input.positions[static_cast<size_t>(v)].x();
    EXPECT_NEAR(p[Param::mean_lifetime][v], 2.0 * x, 1e-15);
    sinks += p[Param::mean_lifetime][v] == 0.0 ? 1 : 0;
  }
  EXPECT_GT(sinks, 0);
  j["mean_lifetime"] = 0.0;
  EXPECT_NE(scene_error(j).find("key 'mean_lifetime'"), std::string::npos);
}

// Eq. 5's U is the steady mean only where every agent deposits at one rate with one active
// fraction against one decay: maps on those parameters, write-stimuli and a terminating boundary
// break it; maps on the others, read-stimuli, spawn weights and a bias do not.
TEST(SceneMaps, TheSteadyMeanIsUOnlyWhereEq5Applies) {
  TempDir dir;
  auto with = [&](const json& changes) {
    json j = base_scene();
    j["maps"] = square_maps();
    for (auto it = changes.begin(); it != changes.end(); ++it) j[it.key()] = it.value();
    return steady_mean_is_U(load_scene(write_scene(dir, j)));
  };
  EXPECT_TRUE(with(json::object()));
  EXPECT_TRUE(with({{"sensor_distance", {{"map", "ramp_x"}, {"range", {0.02, 0.06}}}}}));
  EXPECT_TRUE(with({{"read_stimuli", {{{"map", "ramp_x"}, {"weight", 2.0}}}}, {"spawn_weight", "ramp_x"}}));
  EXPECT_TRUE(with({{"bias", {{"direction", "east"}, {"strength", 10}}}}));
  EXPECT_FALSE(with({{"deposit_rate", {{"map", "ramp_x"}, {"range", {0.5, 1.5}}}}}));
  EXPECT_FALSE(with({{"decay_rate", {{"map", "ramp_x"}, {"range", {0.5, 1.5}}}}}));
  EXPECT_FALSE(with({{"mean_lifetime", {{"map", "ramp_x"}, {"range", {0.0, 2.0}}}}}));
  EXPECT_FALSE(with({{"activation_time", {{"map", "ramp_x"}, {"range", {0.0, 0.4}}}}}));
  EXPECT_FALSE(with({{"write_stimuli", {{{"map", "ramp_x"}, {"rate", 1.0}}}}}));
  EXPECT_FALSE(with({{"boundary", "terminate"}}));
}

TEST(SceneMaps, ControlsAreTheDocumentedSumsAndConversions) {
  TempDir dir;
  json j = base_scene();
  j["maps"] = square_maps();
  j["read_stimuli"] = {{{"map", "ramp_x"}, {"weight", 0.5}}, {{"map", "two"}, {"weight", -0.25}}};
  j["write_stimuli"] = {{{"map", "ramp_y"}, {"rate", 2.0}}, {{"map", "ramp_x"}, {"rate", -1.0}}};
  j["spawn_weight"] = "ramp_x";
  j["bias"] = {{"direction", "east"}, {"strength", 90.0}, {"symmetry", 4}};
  j["spawn_heading"] = "bias";
  j["boundary"] = "terminate";
  const Scene scene = load_scene(write_scene(dir, j));
  const PreparedSurface surface = prepare_scene_surface(scene);
  const SimulationControls c = simulation_controls(scene, surface);
  const int n = surface.domain.vertex_count;
  ASSERT_EQ(static_cast<int>(c.read_stimulus.size()), n);
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector3d x = surface.input.positions[static_cast<size_t>(v)];  // unrefined: intrinsic = input
    EXPECT_NEAR(c.read_stimulus[v], 0.5 * x.x() - 0.25 * 2.0, 1e-15);
    EXPECT_NEAR(c.write_rate[v], 2.0 * x.y() - x.x(), 1e-15);
    EXPECT_NEAR(c.spawn_weight[v], x.x(), 1e-15);
  }
  ASSERT_TRUE(c.bias.has_value());
  EXPECT_EQ(c.bias->symmetry, 4);
  for (int v = 0; v < n; ++v) EXPECT_NEAR(c.bias->strength[v], std::numbers::pi / 2, 1e-15);  // 90 deg/s in rad/s
  ASSERT_EQ(static_cast<int>(c.bias->direction.size()), surface.domain.face_count);
  EXPECT_NEAR(std::hypot(c.bias->direction[0][0], c.bias->direction[0][1]), 1.0, 1e-12);
  EXPECT_EQ(c.spawn_heading, SpawnHeading::Bias);
  EXPECT_EQ(c.boundary, BoundaryBehaviour::Terminate);
}

TEST(SceneMaps, BadReferencesAreRefusedNamingTheKey) {
  struct Case {
    json changes;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases = {
      {{{"sensor_distance", "nope"}}, {"key 'sensor_distance' = \"nope\": map 'nope' is not defined in 'maps'"}},
      {{{"sensor_distance", "east"}}, {"key 'sensor_distance'", "'east' is a vector map, but a scalar map is needed"}},
      {{{"sensor_distance", {{"map", "ramp_x"}, {"range", {-0.1, 0.1}}}}}, {"key 'sensor_distance'", "bound -0.1", "out of range"}},
      {{{"sensor_distance", {{"map", "ramp_x"}, {"range", {0.1}}}}}, {"key 'sensor_distance'", "two numbers"}},
      {{{"sensor_distance", {{"map", "ramp_x"}, {"scale", 2}}}}, {"key 'sensor_distance'", "unknown field \"scale\""}},
      {{{"sensor_distance", "negative"}}, {"key 'sensor_distance'", "map 'negative' gives -1 m at intrinsic vertex 0", "out of range"}},
      {{{"decay_rate", {{"map", "ramp_x"}}}}, {"key 'decay_rate'", "map 'ramp_x' gives 0 1/s", "must be > 0"}},
      {{{"read_stimuli", {{{"map", "nope"}, {"weight", 1}}}}}, {"key 'read_stimuli[0]'", "map 'nope'"}},
      {{{"read_stimuli", {{{"map", "east"}, {"weight", 1}}}}}, {"key 'read_stimuli[0]'", "vector map"}},
      {{{"read_stimuli", {{{"map", "two"}}}}}, {"key 'read_stimuli[0]'", "missing \"weight\""}},
      {{{"write_stimuli", {{{"map", "two"}, {"weight", 1}}}}}, {"key 'write_stimuli[0]'", "unknown field \"weight\""}},
      {{{"write_stimuli", {{"map", "two"}, {"rate", 1}}}}, {"key 'write_stimuli'", "must be a list"}},
      {{{"write_stimuli", {2}}}, {"key 'write_stimuli[0]'", "must be an object"}},
      {{{"spawn_weight", 0}}, {"key 'spawn_weight'", "all spawn weights are zero"}},
      {{{"spawn_weight", "nowhere"}}, {"key 'spawn_weight'", "map 'nowhere' is zero everywhere"}},
      {{{"spawn_weight", "negative"}}, {"key 'spawn_weight'", "must be >= 0"}},
      {{{"spawn_weight", "east"}}, {"key 'spawn_weight'", "vector map"}},
      {{{"bias", {{"direction", "ramp_x"}, {"strength", 10}}}}, {"key 'bias'", "'ramp_x' is a scalar map, but a vector map is needed"}},
      {{{"bias", {{"direction", "east"}, {"strength", "east"}}}}, {"key 'bias'", "'east' is a vector map"}},
      {{{"bias", {{"direction", "east"}, {"strength", -5}}}}, {"key 'bias'", "must be >= 0"}},
      {{{"bias", {{"direction", "east"}, {"strength", "negative"}}}}, {"key 'bias'", "\"strength\" gives -1 deg/s"}},
      {{{"bias", {{"direction", "east"}, {"strength", 10}, {"symmetry", 9}}}}, {"key 'bias'", "1..8"}},
      {{{"bias", {{"direction", "east"}}}}, {"key 'bias'", "missing \"strength\""}},
      {{{"spawn_heading", "bias"}}, {"key 'spawn_heading'", "has no 'bias'"}},
      {{{"spawn_heading", "north"}}, {"key 'spawn_heading'", "\"random\" or \"bias\""}},
      {{{"boundary", "absorb"}}, {"key 'boundary'", "\"reflect\" or \"terminate\""}},
      {{{"maps", {{"w", {{"ply", "missing.ply"}, {"property", "w"}}}}}}, {"key 'maps'", "map 'w'", "file not found"}},
  };
  for (const Case& c : cases) {
    json j = base_scene();
    j["maps"] = square_maps();
    for (auto it = c.changes.begin(); it != c.changes.end(); ++it) j[it.key()] = it.value();
    const std::string message = scene_error(j);
    SCOPED_TRACE(c.changes.dump());
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_NE(message.find("scene.json: key '"), std::string::npos) << message;
    for (const std::string& s : c.says) EXPECT_NE(message.find(s), std::string::npos) << message;
  }
}

// The per-vertex values reach the backend, not a summary of them: with deposit_rate 0 on the left
// half of the square (x <= 1/2) and no diffusion, nothing is ever deposited on a vertex whose faces
// all lie left of x = 1/2, while the right half fills; a backend given the mean deposit rate would
// fill both halves alike.
TEST(SceneMaps, ADepositMapReachesBothBackends) {
  TempDir dir;
  json j = base_scene();
  j["agents"] = 2000;
  j["diffuse_rate"] = 0.0;
  j["maps"] = {{"ramp", {{"axis", "x"}}}, {"right", {{"threshold", "ramp"}, {"at", 0.5 + 1e-9}}}};
  j["deposit_rate"] = {{"map", "right"}, {"range", {0.0, 2.0}}};
  const Scene scene = load_scene(write_scene(dir, j));
  const PreparedSurface surface = prepare_scene_surface(scene);
  const opencl::ComputeContext compute = opencl::make_compute_context("");
  for (const BackendChoice backend : {BackendChoice::Reference, BackendChoice::OpenCL}) {
    const auto sim = make_backend(backend, &compute, surface, scene);
    sim->run(50);
    sim->finish();
    const IntrinsicVertexData<double> field = sim->field_values();
    double left = 0.0, right = 0.0;
    for (int v = 0; v < surface.domain.vertex_count; ++v) {
      const double x = surface.input.positions[static_cast<size_t>(v)].x();  // unrefined: intrinsic = input
      if (x < 0.45) left += field[v];
      if (x > 0.55) right += field[v];
    }
    EXPECT_EQ(left, 0.0) << to_string(backend);
    EXPECT_GT(right, 0.0) << to_string(backend);
  }
}

// A scene on the square with a sensor_distance map and a few maps of each kind, one read from a
// PLY in a subfolder of the scene's folder (paths resolve against it).
std::string map_scene(const TempDir& dir) {
  std::filesystem::create_directories(dir.path / "scenes" / "data");
  const InputMesh square = prepare_surface(SurfaceSpec{"shape:square", {}, {}, 0.0}).input;
  InputVertexData<double> w(static_cast<size_t>(square.vertex_count()));
  for (int v = 0; v < square.vertex_count(); ++v) w[v] = 0.25 + 0.5 * square.positions[static_cast<size_t>(v)].y();
  write_field_ply((dir.path / "scenes" / "data" / "w.ply").string(), square, w, {}, "weight");
  json j = base_scene();
  j["scale_to_area"] = 4.0;
  j["max_circumradius"] = 0.1;
  j["maps"] = {{"ramp", {{"axis", "x"}}},
               {"painted", {{"ply", "data/w.ply"}, {"property", "weight"}}},
               {"spot", {{"sphere", {{"center", {0.5, 0.5, 0.0}}, {"radius", 0.2}}}, {"falloff", 0.1}}},
               {"both", {{"product", {"painted", "spot"}}}},
               {"diagonal", {{"direction", {1.0, 1.0, 0.5}}}}};
  j["sensor_distance"] = {{"map", "ramp"}, {"range", {0.03, 0.08}}};
  j["read_stimuli"] = {{{"map", "both"}, {"weight", 0.5}}};
  j["bias"] = {{"direction", "diagonal"}, {"strength", 20.0}};
  return write_scene(dir, j, "scenes/maps.json");
}

TEST(SceneMaps, ASensorDistanceMapRunsOnBothBackends) {
  TempDir dir;
  const std::string scene = map_scene(dir);
  for (const char* backend : {"reference", "opencl"}) {
    const std::filesystem::path out = dir.path / backend;
    const auto r = run_physarum("run " + quoted(std::filesystem::path(scene)) + " --backend " + backend + " --steps 5 --out " + quoted(out) +
                                " --maps-out " + quoted(dir.path / (std::string(backend) + "_maps.ply")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(out / "run.json");
    const json run = json::parse(in);
    EXPECT_EQ(run["backend"], backend);
    EXPECT_EQ(run["parameters"]["sensor_distance"]["map"], "ramp");
    // The square's x-ramp averages 1/2 (its grid is symmetric about x = 1/2): 0.03 + 0.05 / 2.
    EXPECT_NEAR(run["parameters"]["sensor_distance"]["mean"].get<double>(), 0.055, 1e-9);
    EXPECT_TRUE(std::filesystem::exists(dir.path / (std::string(backend) + "_maps.ply")));
  }
}

TEST(SceneMaps, MapCommandWritesTheEvaluatedValues) {
  TempDir dir;
  const std::string scene_path = map_scene(dir);
  const std::filesystem::path ply = dir.path / "maps.ply";
  const auto r = run_physarum("map " + quoted(std::filesystem::path(scene_path)) + " --out " + quoted(ply));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // The same evaluation here, in process.
  const Scene scene = load_scene(scene_path);
  const PreparedSurface surface = prepare_scene_surface(scene);
  const EvaluatedMaps maps = evaluate_maps(scene.maps, surface, scene_path);
  const InputMaps expected = maps_on_input(scene.maps, surface, maps, scene_path);

  const PlyFields read = read_ply_fields(ply.string());
  ASSERT_EQ(read.mesh.vertex_count(), surface.input.vertex_count());
  ASSERT_EQ(read.mesh.triangles, surface.input.triangles);
  ASSERT_EQ(expected.scalar.size(), 4u);
  for (const auto& [name, values] : expected.scalar) {
    const std::vector<double>& column = read.property(name);
    ASSERT_EQ(column.size(), values.size()) << name;
    for (size_t v = 0; v < values.size(); ++v) ASSERT_EQ(column[v], static_cast<float>(values[v])) << name << " " << v;
  }
  // The PLY map itself: its values at the input vertices are the file's (a map read back whole).
  const std::vector<double>& painted = read.property("painted");
  for (int v = 0; v < surface.input.vertex_count(); ++v)
    ASSERT_FLOAT_EQ(static_cast<float>(painted[static_cast<size_t>(v)]),
                    static_cast<float>(0.25 + 0.5 * surface.input.positions[static_cast<size_t>(v)].y()));
  ASSERT_EQ(expected.vector.size(), 1u);
  const auto& [name, vectors] = expected.vector.front();
  for (int c = 0; c < 3; ++c) {
    const std::vector<double>& column = read.face_property(name + "_" + static_cast<char>('x' + c));
    ASSERT_EQ(column.size(), vectors.size());
    for (size_t f = 0; f < vectors.size(); ++f) ASSERT_EQ(column[f], static_cast<float>(vectors[f][c])) << f;
  }
  // In input coordinates and projected into the square's plane: (1, 1, 0).
  EXPECT_EQ(vectors.front(), Eigen::Vector3d(1.0, 1.0, 0.0));

  // A scene without maps: exit 1 and nothing written.
  TempDir plain;
  const auto none = run_physarum("map " + quoted(std::filesystem::path(write_scene(plain, base_scene()))) + " --out " + quoted(plain.path / "m.ply"));
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("defines no maps"), std::string::npos) << none.err;
  EXPECT_FALSE(std::filesystem::exists(plain.path / "m.ply"));
}

}  // namespace
}  // namespace physarum
