#include "common/setup/workload.hpp"

#include "common/scene/default_scene.hpp"
#include "common/base/errors.hpp"

namespace physarum {

BackendChoice parse_backend_choice(const std::string& name) {
  if (name == "reference") return BackendChoice::Reference;
  if (name == "opencl") return BackendChoice::OpenCL;
  throw UsageError("unknown backend '" + name + "' (reference or opencl)");
}

const char* to_string(BackendChoice backend) { return backend == BackendChoice::OpenCL ? "opencl" : "reference"; }

SurfaceSpec bench_surface(const std::string& mesh, double max_circumradius) {
  SurfaceSpec s;
  s.mesh = mesh;
  s.scale_to_area = kBenchArea;
  s.max_circumradius = max_circumradius;
  return s;
}

Workload bench_workload(const std::string& label, const std::string& mesh, double max_circumradius, const Scene& scene,
                        BackendChoice backend) {
  return Workload{label, bench_surface(mesh, max_circumradius), scene, backend};
}

Scene bench_scene(int agents) { return default_scene_parameters(agents); }

double agent_step_face_visits(double crossings_per_agent_step) { return crossings_per_agent_step + 1.6; }

double agent_step_bytes(double crossings_per_agent_step) {
  return 88.0 + 64.0 * agent_step_face_visits(crossings_per_agent_step) + 4.0 * 9.0 * 0.6 + 24.0;
}

}  // namespace physarum

namespace physarum {

const PreparedSurface& SurfaceCache::get(const SurfaceSpec& spec) {
  const Key key{spec.mesh, spec.scale_to_area.value_or(-1.0), spec.max_circumradius.value_or(-1.0), spec.min_angle_deg};
  auto it = surfaces_.find(key);
  if (it == surfaces_.end()) it = surfaces_.emplace(key, std::make_unique<PreparedSurface>(prepare_surface(spec))).first;
  return *it->second;
}

}  // namespace physarum
