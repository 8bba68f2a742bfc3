#pragma once
// Two small scenes the session tests share: an agent scene and a Gray-Scott one on the octagonal
// prism (closed, so diffusion conserves each integral), both a few milliseconds a step.
#include <nlohmann/json.hpp>

namespace physarum::testing {

inline nlohmann::json agent_scene_json() {
  return {{"mesh", "shape:octagonal-prism"}, {"scale_to_area", 1.0}, {"max_circumradius", 0.03}, {"agents", 400},
          {"time_step", 0.01}, {"seed", 3}, {"sensor_distance", 0.05}, {"sensor_angle", 22.5}, {"move_rate", 0.5},
          {"turn_rate", 180.0}, {"turn_frequency", 20.0}, {"deposit_rate", 1.0}, {"decay_rate", 1.0},
          {"diffuse_rate", 0.0002}, {"mean_lifetime", 1.0}, {"activation_time", 0.2}};
}

inline nlohmann::json reaction_scene_json() {
  return {{"mesh", "shape:octagonal-prism"}, {"scale_to_area", 1.0}, {"max_circumradius", 0.03}, {"model", "gray-scott"},
          {"time_step", 1.0}, {"seed", 5}, {"initial", {{"noise", 0.01}, {"spots", {{"count", 3}, {"radius", 0.1},
          {"values", {{"u", 0.5}, {"v", 0.25}}}}}}}};
}

}  // namespace physarum::testing
