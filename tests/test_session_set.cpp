// Live changes (Session::set, api/session.hpp): a key the running model takes on the fly applies from
// the next step, continuing the state bit for bit; one that needs a new run, or a bad value, is
// refused naming the key and changes nothing. Checked by what the changed model must do, not by
// its own numbers: without deposit the pheromone's integral only decays, by the same factor every
// step (diffusion conserves it); with F = k = 0 Gray-Scott only moves mass between u and v, so the
// integral of u + v stays put.
#include "api/session.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "session_scenes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace physarum {
namespace {

using nlohmann::json;

using testing::agent_scene_json;
using testing::reaction_scene_json;

SessionOptions on(const std::string& backend) {
  SessionOptions o;
  o.backend = backend;
  o.use_map_cache = false;
  return o;
}

double integral(const Session& session, int layer) {
  const IntrinsicVertexData<double> values = session.field(layer);
  const IntrinsicVertexData<double>& mass = session.surface().domain.vertex_mass;
  double sum = 0.0;
  for (size_t v = 0; v < values.size(); ++v) sum += mass[v] * values[v];
  return sum;
}

class SessionSet : public ::testing::TestWithParam<const char*> {};

TEST_P(SessionSet, AnUnchangedValueContinuesBitForBitAsIfNothingWasSet) {
  Session changed(scene_from_json(agent_scene_json()), on(GetParam()));
  Session plain(scene_from_json(agent_scene_json()), on(GetParam()));
  changed.step(15);
  plain.step(15);
  EXPECT_EQ(changed.set("sensor_angle", 22.5), 15);  // a new backend, given the state of the old one
  changed.step(25);
  plain.step(25);
  EXPECT_EQ(changed.field(0).values(), plain.field(0).values());
  EXPECT_EQ(changed.steps_taken(), 40);
}

TEST_P(SessionSet, WithoutDepositThePheromoneOnlyDecaysByTheSameFactorEveryStep) {
  Session session(scene_from_json(agent_scene_json()), on(GetParam()));
  session.step(20);
  session.set("deposit_rate", 0.0);
  EXPECT_EQ(session.scene().agent_model().parameters[Param::deposit_rate], 0.0);
  std::vector<double> integrals{integral(session, 0)};
  for (int s = 0; s < 4; ++s) {
    session.step(1);
    integrals.push_back(integral(session, 0));
  }
  const double factor = integrals[1] / integrals[0];
  EXPECT_LT(factor, 1.0);
  EXPECT_GT(factor, 0.98);  // decay_rate 1/s over 0.01 s
  for (size_t s = 1; s + 1 < integrals.size(); ++s)
    EXPECT_NEAR(integrals[s + 1] / integrals[s], factor, std::string(GetParam()) == "opencl" ? 1e-6 : 1e-12) << s;
  // ... and a changed run's checkpoint is the changed scene's.
  Session original(scene_from_json(agent_scene_json()), on(GetParam()));
  testing::TempDir dir;
  session.save((dir.path / "changed.bin").string());
  EXPECT_THROW(original.restore((dir.path / "changed.bin").string()), InputError);
}

TEST_P(SessionSet, GrayScottWithoutFeedAndKillMovesMassBetweenUAndVOnly) {
  Session session(scene_from_json(reaction_scene_json()), on(GetParam()));
  session.step(10);
  session.set("parameters.F", 0.0);
  session.set("parameters.k", 0.0);
  const double before = integral(session, 0) + integral(session, 1);
  session.step(30);
  const double after = integral(session, 0) + integral(session, 1);
  // Diffusion conserves each integral on a closed surface; -u v^2 and +u v^2 cancel. float32 on a device.
  EXPECT_NEAR(after, before, (std::string(GetParam()) == "opencl" ? 1e-5 : 1e-11) * before);
  EXPECT_LT(integral(session, 1), integral(session, 0) + integral(session, 1));
}

TEST_P(SessionSet, AKeyThatNeedsANewRunOrABadValueIsRefusedAndChangesNothing) {
  Session session(scene_from_json(agent_scene_json()), on(GetParam()));
  session.step(5);
  const std::vector<double> before = session.field(0).values();
  auto message = [&](const std::string& key, const json& value) {
    return testing::input_error_of([&] { session.set(key, value); });
  };
  EXPECT_NE(message("agents", 10).find("scene: agents: needs a new run"), std::string::npos);
  EXPECT_NE(message("max_circumradius", 0.02).find("max_circumradius: needs a new run"), std::string::npos);
  EXPECT_NE(message("sensor_angle", "wide").find("sensor_angle: expected a number, got \"wide\""), std::string::npos);
  EXPECT_NE(message("decay_rate", 0.0).find("scene: key 'decay_rate' = 0 is out of range (must be > 0)"),
            std::string::npos);
  EXPECT_EQ(session.field(0).values(), before);
  EXPECT_EQ(session.steps_taken(), 5);
  EXPECT_EQ(session.scene().agent_model().parameters[Param::sensor_angle], 22.5 * std::acos(-1.0) / 180.0);

  Session reaction(scene_from_json(reaction_scene_json()), on(GetParam()));
  const std::string unknown = testing::input_error_of([&] { reaction.set("parameters.Q", 1.0); });
  EXPECT_NE(unknown.find("parameters.Q: gray-scott has no coefficient 'Q'"), std::string::npos) << unknown;
  const std::string diffusion = testing::input_error_of([&] { reaction.set("morphogens.u.diffusion", 1e-5); });
  EXPECT_NE(diffusion.find("morphogens.u.diffusion: needs a new run"), std::string::npos) << diffusion;
}

INSTANTIATE_TEST_SUITE_P(Backends, SessionSet, ::testing::Values("reference", "opencl"));

TEST(SessionSetGrowth, TheGrowthModelTakesNoKeyOnTheFly) {
  const Scene scene = load_scene(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/growth_cap.json");
  Session session(scene, on("reference"));
  const std::string message = testing::input_error_of([&] { session.set("shell.thickness", 0.01); });
  EXPECT_NE(message.find("shell.thickness: needs a new run (the growth model takes no key on the fly"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace physarum
