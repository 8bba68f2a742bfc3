#pragma once
// One description of a workload, shared by the tests, the benchmark suites (bench/), `physarum
// bench` and `physarum_device_check` (as CLBlast shares one routine description between its test
// and its benchmark): which surface (mesh, area, refinement), which model parameters and how many
// agents, which backend, and the bytes an agent step moves where a benchmark reports a roofline.
#include "common/scene/scene.hpp"
#include "common/setup/scene_surface.hpp"

#include <string>

namespace physarum {

enum class BackendChoice { Reference, OpenCL };

// "reference" or "opencl"; UsageError otherwise.
BackendChoice parse_backend_choice(const std::string& name);
const char* to_string(BackendChoice backend);

struct Workload {
  std::string label;     // the surface as reports name it ("spot.obj", "shape:sphere")
  SurfaceSpec surface;   // how the surface is built (prepare_surface, through a SurfaceCache)
  Scene scene;           // model parameters; scene.agent_model().agents is the size
  BackendChoice backend = BackendChoice::Reference;
};

// The benchmarks' surfaces: `mesh` (a file path or shape:NAME) scaled to 4 m^2 and refined to
// `max_circumradius` metres.
constexpr double kBenchArea = 4.0;
SurfaceSpec bench_surface(const std::string& mesh, double max_circumradius);

// A benchmark workload: `scene` on bench_surface(mesh, max_circumradius), labelled `label`.
Workload bench_workload(const std::string& label, const std::string& mesh, double max_circumradius, const Scene& scene,
                        BackendChoice backend);

// The default scene's parameters (tools/scenes/default.json) with `agents` agents: the model the
// benchmarks time.
Scene bench_scene(int agents);

// Bytes an agent step moves from memory when nothing is reused (the roofline's model): its state
// read and written (face 4, position 8, heading 8, five floats 20, id 4 = 44 B each way), one
// 64-byte face record per face visited (the crossings plus one start face per walk: 1 move + 3/5
// sensing), three concentration reads per sensor and three 8-byte deposit atomics per movement
// piece.
double agent_step_bytes(double crossings_per_agent_step);
// Faces an agent step visits: its crossings plus the start face of each walk.
double agent_step_face_visits(double crossings_per_agent_step);

}  // namespace physarum

#include <map>
#include <memory>
#include <tuple>

namespace physarum {

// Surfaces built once and kept (the benchmarks time many workloads on one surface).
class SurfaceCache {
 public:
  const PreparedSurface& get(const SurfaceSpec& spec);

 private:
  using Key = std::tuple<std::string, double, double, double>;
  std::map<Key, std::unique_ptr<PreparedSurface>> surfaces_;
};

}  // namespace physarum
