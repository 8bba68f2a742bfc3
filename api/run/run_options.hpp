#pragma once
// What `physarum run` was asked to do (tools/run/command_run.cpp), in a form a checkpoint can carry: a
// resumed run (`physarum run --resume DIR`) takes every option back from DIR/checkpoint.bin, so it
// continues the very run that was stopped, and the scene's identity hash lets it refuse a scene
// that changed in between.
#include "api/run/surface_exports.hpp"

#include "api/session.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct RunOptions {
  std::string scene;
  // The scene as JSON text when it comes from code, not from a file (the Python module's Scene): what
  // the identity hash covers instead of the file's bytes. "" for a file.
  std::string scene_text;
  std::vector<std::string> sets;  // --set KEY=VALUE (common/scene/scene_overrides.hpp), in the order given
  std::string backend = "auto";
  std::string device;  // --device SPEC (auto or opencl); "" = $PHYSARUM_DEVICE or the default choice
  std::optional<long long> steps;
  std::optional<double> sim_time;
  std::optional<std::uint32_t> seed;
  std::string out = "out";
  int frames = 0;  // --frames K: a time-lapse of K pictures (0 = none)
  TextureSettings texture;  // --texture-size, --texture-margin, --texture-format
  std::string maps_out;  // --maps-out FILE: the scene's named maps on the input mesh ("" = none)
  std::optional<double> checkpoint_every;  // --checkpoint-every T: simulated seconds between checkpoints
  std::string resume;  // --resume DIR: continue the run whose checkpoint is DIR/checkpoint.bin
  // The run's notes for its user (the backend chosen, the maps, sub-steps, a resume, a mesh without
  // UVs): `physarum run` prints them on stderr, Python hands them to `logging`; none: quiet. Not
  // part of a checkpoint.
  SurfaceNote log;

  // The --set assignments as one overrides object for load_scene (UsageError on a malformed one or
  // a key given twice).
  nlohmann::json overrides() const;
};

// The options as a checkpoint stores them (scene and out as absolute paths, so a resume works from
// any working directory), and back (InputError naming `where` when a key is missing or mistyped).
nlohmann::json run_options_json(const RunOptions& o);
RunOptions run_options_from_json(const nlohmann::json& j, const std::string& where);

// What the run simulates, hashed (common/base/content_hash.hpp): the scene file's bytes, the overrides,
// the seed override and the mesh file's bytes (not for shape:NAME). A checkpoint stores it; a
// resume whose hash differs is refused. `mesh` is the scene's resolved mesh (Scene::mesh).
std::string scene_identity_hash(const RunOptions& o, const std::string& mesh);

// The library session a run builds (api/session.hpp): the backend and device asked for, the run
// length the feasibility checks judge, and the run's notes (options.log).
SessionOptions session_options(const RunOptions& options, long long steps);


}  // namespace physarum
