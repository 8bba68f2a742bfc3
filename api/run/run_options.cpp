#include "api/run/run_options.hpp"

#include "common/base/content_hash.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene_overrides.hpp"

#include <filesystem>

namespace physarum {

nlohmann::json RunOptions::overrides() const {
  nlohmann::json j = nlohmann::json::object();
  for (const std::string& text : sets) {
    auto [key, value] = parse_scene_assignment(text, "--set");
    if (j.contains(key)) throw UsageError("--set: key '" + key + "' given twice");
    j[key] = std::move(value);
  }
  return j;
}

nlohmann::json run_options_json(const RunOptions& o) {
  nlohmann::json j;
  j["scene"] = std::filesystem::absolute(o.scene).lexically_normal().string();
  j["sets"] = o.sets;
  j["backend"] = o.backend;
  j["device"] = o.device;
  j["steps"] = o.steps ? nlohmann::json(*o.steps) : nlohmann::json();
  j["sim_time"] = o.sim_time ? nlohmann::json(*o.sim_time) : nlohmann::json();
  j["seed"] = o.seed ? nlohmann::json(*o.seed) : nlohmann::json();
  j["out"] = std::filesystem::absolute(o.out).lexically_normal().string();
  j["frames"] = o.frames;
  j["texture"] = o.texture.to_json();
  j["maps_out"] = o.maps_out.empty() ? std::string() : std::filesystem::absolute(o.maps_out).lexically_normal().string();
  j["checkpoint_every"] = o.checkpoint_every ? nlohmann::json(*o.checkpoint_every) : nlohmann::json();
  return j;
}

RunOptions run_options_from_json(const nlohmann::json& j, const std::string& where) {
  try {
    RunOptions o;
    o.scene = j.at("scene").get<std::string>();
    o.sets = j.at("sets").get<std::vector<std::string>>();
    o.backend = j.at("backend").get<std::string>();
    o.device = j.at("device").get<std::string>();
    if (!j.at("steps").is_null()) o.steps = j.at("steps").get<long long>();
    if (!j.at("sim_time").is_null()) o.sim_time = j.at("sim_time").get<double>();
    if (!j.at("seed").is_null()) o.seed = j.at("seed").get<std::uint32_t>();
    o.out = j.at("out").get<std::string>();
    o.frames = j.at("frames").get<int>();
    o.texture = TextureSettings::from_json(j.at("texture"), where + " texture");
    o.maps_out = j.at("maps_out").get<std::string>();
    if (!j.at("checkpoint_every").is_null()) o.checkpoint_every = j.at("checkpoint_every").get<double>();
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": the run's options are unreadable: " + e.what());
  }
}

std::string scene_identity_hash(const RunOptions& o, const std::string& mesh) {
  ContentHasher h;
  h.add(hex64(o.scene_text.empty() ? file_content_hash(o.scene) : content_hash(o.scene_text)));
  h.add("\noverrides ");
  h.add(o.overrides().dump());
  h.add("\nseed ");
  h.add(o.seed ? std::to_string(*o.seed) : std::string("scene"));
  h.add("\nmesh ");
  h.add(mesh.rfind("shape:", 0) == 0 ? mesh : hex64(file_content_hash(mesh)));
  return hex64(h.digest());
}

SessionOptions session_options(const RunOptions& options, long long steps) {
  SessionOptions s;
  s.backend = options.backend;
  s.device = options.device;
  s.planned_steps = steps;
  s.log = options.log;
  return s;
}

}  // namespace physarum
