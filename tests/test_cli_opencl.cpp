// `physarum run --backend opencl` and `physarum bench` as a user runs them: the OpenCL run writes the
// same four outputs as the reference, reproducibly, with run.json naming the device and counting
// sensor crossings; device choice errors are clear; the quick benchmark writes its report, CSV and
// plots with the documented keys.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace physarum::testing {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_scene(const std::filesystem::path& path) {
  std::ofstream(path) << R"({
  "mesh": "shape:square", "scale_to_area": 2.0, "agents": 2000, "time_step": 0.01,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3
})";
}

TEST(OpenCLRunCommand, WritesTheFourOutputsReproduciblyAndNamesTheDevice) {
  TempDir dir;
  write_scene(dir.path / "scene.json");
  const std::string scene = quoted(dir.path / "scene.json");
  const auto a = dir.path / "a", b = dir.path / "b";
  const CommandResult r1 = run_physarum("run " + scene + " --backend opencl --steps 100 --out " + quoted(a));
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const CommandResult r2 = run_physarum("run " + scene + " --backend opencl --device 0 --steps 100 --out " + quoted(b));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  // Fixed-point deposits make the device run deterministic: the same bytes twice.
  for (const char* name : {"pheromone.ply", "stats.csv", "preview.png"}) {
    ASSERT_TRUE(std::filesystem::exists(a / name)) << name;
    EXPECT_EQ(slurp(a / name), slurp(b / name)) << name;
  }
  const nlohmann::json j = nlohmann::json::parse(slurp(a / "run.json"));
  EXPECT_EQ(j["backend"], "opencl");
  EXPECT_NE(j["device"].get<std::string>().find("/"), std::string::npos) << j["device"];
  EXPECT_EQ(j["steps"], 100);
  // Crossings per agent-step count the sensors too: more than the movement's alone.
  EXPECT_GT(j["face_crossings_per_agent_step"].get<double>(), j["move_crossings_per_agent_step"].get<double>());
  EXPECT_GT(j["agent_steps_per_second"].get<double>(), 0.0);
}

TEST(OpenCLRunCommand, DeviceErrorsAreClear) {
  TempDir dir;
  write_scene(dir.path / "scene.json");
  const std::string scene = quoted(dir.path / "scene.json");
  const CommandResult none = run_physarum("run " + scene + " --backend opencl --device no-such-device --steps 2 --out " +
                                          quoted(dir.path / "x"));
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("no-such-device"), std::string::npos) << none.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "x")) << "nothing may be written when the device is missing";
  const CommandResult wrong =
      run_physarum("run " + scene + " --backend reference --device 0 --steps 2 --out " + quoted(dir.path / "y"));
  EXPECT_EQ(wrong.exit_code, 2) << "--device does not go with --backend reference";
}

// --backend auto (the default) takes the OpenCL backend where a device exists and says so; with no
// OpenCL platform at all (an ICD loader pointed at an empty vendor list) it falls back to the
// reference, unless a device was asked for.
TEST(OpenCLRunCommand, AutoBackendTakesTheDeviceWhereThereIsOneAndTheReferenceOtherwise) {
  TempDir dir;
  write_scene(dir.path / "scene.json");
  const std::string scene = quoted(dir.path / "scene.json");
  const CommandResult with_device = run_physarum("run " + scene + " --steps 2 --out " + quoted(dir.path / "a"));
  ASSERT_EQ(with_device.exit_code, 0) << with_device.err;
  nlohmann::json j = nlohmann::json::parse(slurp(dir.path / "a" / "run.json"));
  EXPECT_EQ(j["backend"], "opencl");
  EXPECT_EQ(j["backend_requested"], "auto");
  EXPECT_NE(with_device.err.find("opencl backend (auto:"), std::string::npos) << with_device.err;

  ::setenv("OCL_ICD_VENDORS", (dir.path / "no-vendors").c_str(), 1);
  const CommandResult without = run_physarum("run " + scene + " --steps 2 --out " + quoted(dir.path / "b"));
  const CommandResult asked = run_physarum("run " + scene + " --device 0 --steps 2 --out " + quoted(dir.path / "c"));
  ::unsetenv("OCL_ICD_VENDORS");
  ASSERT_EQ(without.exit_code, 0) << without.err;
  j = nlohmann::json::parse(slurp(dir.path / "b" / "run.json"));
  EXPECT_EQ(j["backend"], "reference");
  EXPECT_NE(without.err.find("reference backend (auto: no OpenCL device"), std::string::npos) << without.err;
  EXPECT_EQ(asked.exit_code, 1) << "a device that was asked for and is missing stays an error";
  EXPECT_FALSE(std::filesystem::exists(dir.path / "c"));
}

TEST(BenchCommand, QuickRunWritesItsReportCsvAndPlots) {
  TempDir dir;
  const CommandResult r = run_physarum("bench --quick --out " + quoted(dir.path));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  for (const char* name :
       {"bench.json", "bench.csv", "agents.png", "faces.png", "faces_scaled.png", "agents_throughput.png",
        "faces_throughput.png"})
    EXPECT_TRUE(std::filesystem::exists(dir.path / name)) << name;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir.path / "bench.json"));
  for (const char* key : {"device", "rows", "pheromone_steps", "paper_case", "roofline", "slopes"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["paper_case"]["agents"], 350000);
  EXPECT_EQ(j["paper_case"]["steps"], 102);
  EXPECT_NEAR(j["paper_case"]["faces"].get<double>(), 46000.0, 2000.0);
  bool both = false;
  for (const auto& row : j["rows"]) both = both || row["backend"] == "reference";
  EXPECT_TRUE(both);
  // The sweep with constant work per face keeps crossings per agent-step constant as the mesh is
  // refined (lengths scale with the edge length); at fixed lengths they grow like sqrt(faces).
  auto crossings_spread = [&](const std::string& sweep) {
    double lo = 1e300, hi = 0.0;
    for (const auto& row : j["rows"])
      if (row["sweep"] == sweep && row["backend"] == "opencl") {
        lo = std::min(lo, row["crossings_per_agent_step"].get<double>());
        hi = std::max(hi, row["crossings_per_agent_step"].get<double>());
      }
    return hi / lo;
  };
  EXPECT_LT(crossings_spread("faces_scaled"), 1.3);
  EXPECT_GT(crossings_spread("faces"), 1.5);
  EXPECT_TRUE(j["slopes"].contains("faces_scaled"));
  // The in-cache rows: doubling the sensor distance and speed doubles the length walked, so the
  // crossings per agent-step (on the same mesh) about double too.
  auto crossings_of = [&](const std::string& sweep) {
    for (const auto& row : j["rows"])
      if (row["sweep"] == sweep && row["backend"] == "opencl") return row["crossings_per_agent_step"].get<double>();
    return 0.0;
  };
  ASSERT_GT(crossings_of("in_cache"), 0.0);
  EXPECT_NEAR(crossings_of("in_cache_x2") / crossings_of("in_cache"), 2.0, 0.3);
  // Each forward pheromone step carries the triad measured beside it.
  for (const auto& p : j["pheromone_steps"]) {
    EXPECT_GT(p["triad_bytes_per_second"].get<double>(), 1e8);
    EXPECT_GT(p["opencl_forward_fraction_of_triad"].get<double>(), 0.0);
  }
  const std::string csv = slurp(dir.path / "bench.csv");
  EXPECT_EQ(csv.rfind("sweep,surface,backend,agents,faces,vertices,seconds_per_step,", 0), 0u) << csv.substr(0, 120);
}

}  // namespace
}  // namespace physarum::testing
