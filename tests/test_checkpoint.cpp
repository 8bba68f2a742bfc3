// Checkpoints (common/run/checkpoint.hpp, SimulationBackend::save_state / restore_state): a state saved
// mid-run and restored into a fresh backend of the same scene continues bit for bit as the
// uninterrupted run (both backends); the file round-trips exactly and refuses corruption, truncation
// and a run it does not belong to.
#include "common/setup/agent_inputs.hpp"
#include "common/run/checkpoint.hpp"
#include "common/base/errors.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/simulation/simulation_state.hpp"
#include "opencl/agent_simulation.hpp"
#include "reference/agent_simulation.hpp"
#include "model_scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>

namespace physarum {
namespace {

const SurfaceDomain& sphere() {
  static const PreparedSurface surface = [] {
    SurfaceSpec spec;
    spec.mesh = "shape:sphere";
    return prepare_surface(spec);
  }();
  return surface.domain;
}

// Finite lifetimes, so respawns (the turnover's random draws) happen within the few steps run.
Scene small_scene(Integrator integrator) { return testing::model_scene(300, 0.01, 0.05, integrator); }

void expect_same_state(const SimulationState& a, const SimulationState& b) {
  EXPECT_EQ(a.steps_taken, b.steps_taken);
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.layers.size(), b.layers.size());
  for (size_t l = 0; l < a.layers.size(); ++l)
    for (size_t v = 0; v < a.layers[l].size(); ++v) ASSERT_EQ(a.layers[l][v], b.layers[l][v]) << "layer " << l << " vertex " << v;
  ASSERT_EQ(a.agents.count(), b.agents.count());
  for (int i = 0; i < a.agents.count(); ++i) {
    const size_t k = static_cast<size_t>(i);
    ASSERT_EQ(a.agents.face[k], b.agents.face[k]) << "agent " << i;
    ASSERT_EQ(a.agents.position[k], b.agents.position[k]) << "agent " << i;
    ASSERT_EQ(a.agents.heading[k], b.agents.heading[k]) << "agent " << i;
    ASSERT_EQ(a.agents.age[k], b.agents.age[k]) << "agent " << i;
    ASSERT_EQ(a.agents.exposure_threshold[k], b.agents.exposure_threshold[k]) << "agent " << i;
    ASSERT_EQ(a.agents.time_since_decision[k], b.agents.time_since_decision[k]) << "agent " << i;
  }
  EXPECT_EQ(a.counters.agent_steps, b.counters.agent_steps);
  EXPECT_EQ(a.counters.face_crossings, b.counters.face_crossings);
  EXPECT_EQ(a.counters.sensor_face_crossings, b.counters.sensor_face_crossings);
  EXPECT_EQ(a.counters.respawns, b.counters.respawns);
}

// Runs `make()` for 10 + 23 steps in one go, and again as 10 steps, a save, a fresh backend that
// restores it, and 23 more: the two end states must be identical in every bit. 23 steps cross
// re-sorts of the OpenCL agents (every 8 steps) at other phases than the first run's.
void expect_resume_is_bit_identical(const std::function<std::unique_ptr<SimulationBackend>()>& make) {
  const auto whole = make();
  whole->run(33);
  whole->finish();
  const SimulationState expected = whole->save_state();
  ASSERT_GT(expected.counters.respawns, 0) << "the run must exercise the turnover's random draws";

  const auto first = make();
  first->run(10);
  const SimulationState saved = first->save_state();
  EXPECT_EQ(saved.steps_taken, 10);
  const auto resumed = make();
  resumed->restore_state(saved);
  resumed->run(23);
  resumed->finish();
  expect_same_state(resumed->save_state(), expected);
}

TEST(Checkpoint, ReferenceResumesBitIdentically) {
  for (const Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    const Scene scene = small_scene(integrator);
    expect_resume_is_bit_identical([&] { return std::make_unique<ReferenceAgentSimulation>(sphere(), constant_parameters(scene, sphere()), simulation_settings(scene)); });
  }
}

TEST(Checkpoint, OpenCLResumesBitIdentically) {
  std::optional<opencl::ComputeContext> compute;
  try {
    compute = opencl::make_compute_context("");
  } catch (const DeviceError& e) {
    GTEST_SKIP() << "no OpenCL device: " << e.what();
  }
  for (const Integrator integrator : {Integrator::Forward, Integrator::Backward}) {
    const Scene scene = small_scene(integrator);
    expect_resume_is_bit_identical([&] { return std::make_unique<opencl::OpenCLAgentSimulation>(*compute, sphere(), constant_parameters(scene, sphere()), simulation_settings(scene)); });
  }
}

TEST(Checkpoint, RestoreRefusesAStateThatDoesNotFit) {
  ReferenceAgentSimulation sim(sphere(), constant_parameters(small_scene(Integrator::Forward), sphere()), simulation_settings(small_scene(Integrator::Forward)));
  SimulationState state = sim.save_state();
  state.agents.resize(state.agents.count() - 1);
  EXPECT_THROW(sim.restore_state(state), InputError);
  state = sim.save_state();
  state.layers.push_back(state.layers[0]);
  EXPECT_THROW(sim.restore_state(state), InputError);
  state = sim.save_state();
  state.agents.face[3] = sphere().face_count;
  EXPECT_THROW(sim.restore_state(state), InputError);
}

CheckpointHeader header_of(const SimulationBackend& sim) {
  CheckpointHeader h;
  h.build_id = checkpoint_build_id();
  h.backend = sim.backend_name();
  h.device = sim.device_name();
  h.scene_hash = "0123456789abcdef";
  h.step = sim.steps_taken();
  h.run = {{"stats", "time,mean\n0,1\n"}};
  return h;
}

TEST(CheckpointFile, RoundTripsExactly) {
  ReferenceAgentSimulation sim(sphere(), constant_parameters(small_scene(Integrator::Forward), sphere()), simulation_settings(small_scene(Integrator::Forward)));
  sim.run(7);
  testing::TempDir dir;
  const std::string path = (dir.path / "checkpoint.bin").string();
  write_checkpoint(path, header_of(sim), sim.save_state());
  const Checkpoint c = read_checkpoint(path);
  expect_same_state(c.state, sim.save_state());
  EXPECT_EQ(c.header.step, 7);
  EXPECT_EQ(c.header.backend, "reference");
  EXPECT_EQ(c.header.scene_hash, "0123456789abcdef");
  EXPECT_EQ(c.header.run["stats"], "time,mean\n0,1\n");
  // Only the checkpoint itself is left in the folder (the temporary was renamed).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator()), 1);
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckpointFile, RefusesCorruptionTruncationAndOtherFiles) {
  ReferenceAgentSimulation sim(sphere(), constant_parameters(small_scene(Integrator::Forward), sphere()), simulation_settings(small_scene(Integrator::Forward)));
  sim.run(3);
  const std::string good = checkpoint_bytes(header_of(sim), sim.save_state());
  testing::TempDir dir;
  const std::string path = (dir.path / "checkpoint.bin").string();
  auto write = [&](const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; };

  // One flipped bit, in the header text and deep in the payload.
  for (const size_t at : {size_t{45}, good.size() / 2, good.size() - 1}) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    write(bad);
    EXPECT_NE(message_of([&] { read_checkpoint(path); }).find("corrupted"), std::string::npos) << "byte " << at;
  }
  write(good.substr(0, good.size() - 8));
  EXPECT_NE(message_of([&] { read_checkpoint(path); }).find("truncated"), std::string::npos);
  write("not a checkpoint at all, just some text of sufficient length");
  EXPECT_NE(message_of([&] { read_checkpoint(path); }).find("not a physarum checkpoint"), std::string::npos);
  write(good);
  EXPECT_NO_THROW(read_checkpoint(path));
}

TEST(CheckpointFile, RefusesAnotherRunsCheckpointNamingWhatDiffers) {
  ReferenceAgentSimulation sim(sphere(), constant_parameters(small_scene(Integrator::Forward), sphere()), simulation_settings(small_scene(Integrator::Forward)));
  const CheckpointHeader saved = header_of(sim);
  EXPECT_NO_THROW(check_checkpoint_matches(saved, saved, "c.bin"));
  CheckpointHeader other = saved;
  other.scene_hash = "fedcba9876543210";
  EXPECT_NE(message_of([&] { check_checkpoint_matches(saved, other, "c.bin"); }).find("another scene"), std::string::npos);
  other = saved;
  other.build_id = "0000000000000000";
  EXPECT_NE(message_of([&] { check_checkpoint_matches(saved, other, "c.bin"); }).find("another build"), std::string::npos);
  other = saved;
  other.backend = "opencl";
  EXPECT_NE(message_of([&] { check_checkpoint_matches(saved, other, "c.bin"); }).find("another backend"), std::string::npos);
  other = saved;
  other.device = "a GPU";
  EXPECT_NE(message_of([&] { check_checkpoint_matches(saved, other, "c.bin"); }).find("another device"), std::string::npos);
}

}  // namespace
}  // namespace physarum
