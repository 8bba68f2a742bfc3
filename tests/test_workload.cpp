// One workload description for the tests, the benchmarks, `physarum bench` and the device check
// (common/setup/workload.hpp): the surface it names is built once per spec and has the benchmarks' area,
// and the backend built from it runs the scene it carries.
#include "common/setup/agent_inputs.hpp"
#include "common/setup/workload.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "api/backend_factory.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace physarum {
namespace {

TEST(Workload, SurfacesAreBuiltOncePerSpecAtTheBenchmarkArea) {
  SurfaceCache surfaces;
  const Workload coarse = bench_workload("shape:torus", "shape:torus", 0.04, bench_scene(10), BackendChoice::Reference);
  const Workload fine = bench_workload("shape:torus", "shape:torus", 0.02, bench_scene(10), BackendChoice::Reference);
  const PreparedSurface& a = surfaces.get(coarse.surface);
  EXPECT_EQ(&a, &surfaces.get(coarse.surface)) << "an equal spec must not build the surface again";
  const PreparedSurface& b = surfaces.get(fine.surface);
  EXPECT_NE(&a, &b);
  EXPECT_NEAR(a.domain.total_area, kBenchArea, 1e-9 * kBenchArea);
  EXPECT_NEAR(b.domain.total_area, kBenchArea, 1e-9 * kBenchArea);
  // Halving the circumradius bound on the same surface roughly quadruples the faces (area / h^2).
  EXPECT_GT(b.domain.face_count, 2 * a.domain.face_count);
}

TEST(Workload, BothBackendsRunTheSceneItCarries) {
  SurfaceCache surfaces;
  const opencl::ComputeContext compute = opencl::make_compute_context("");
  for (const BackendChoice backend : {BackendChoice::Reference, BackendChoice::OpenCL}) {
    const Workload w = bench_workload("shape:sphere", "shape:sphere", 0.1, bench_scene(777), backend);
    const auto sim = make_backend(w, surfaces, &compute);
    sim->run(2);
    sim->finish();
    EXPECT_EQ(sim->counters().agent_steps, 2 * 777) << to_string(backend);
    const double U = uniform_steady_state(w.scene, kBenchArea);
    EXPECT_GT(sim->field_statistics(U).mean, 0.0) << to_string(backend) << ": the agents deposited nothing";
  }
}

TEST(Workload, BackendNamesRoundTrip) {
  for (const BackendChoice b : {BackendChoice::Reference, BackendChoice::OpenCL})
    EXPECT_EQ(parse_backend_choice(to_string(b)), b);
  EXPECT_ANY_THROW(parse_backend_choice("cuda"));
}

}  // namespace
}  // namespace physarum
