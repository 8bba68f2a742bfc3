#include "common/scene_json.hpp"

namespace physarum {

nlohmann::ordered_json scene_parameters_json(const Scene& s) {
  constexpr double kDegree = 180.0 / 3.14159265358979323846;
  nlohmann::ordered_json j;
  j["mesh"] = s.mesh;
  j["scale_to_area"] = s.scale_to_area ? nlohmann::ordered_json(*s.scale_to_area) : nlohmann::ordered_json();
  j["max_circumradius"] = s.max_circumradius ? nlohmann::ordered_json(*s.max_circumradius) : nlohmann::ordered_json();
  j["min_angle"] = s.min_angle_deg;
  j["agents"] = s.agents;
  j["time_step"] = s.time_step;
  j["sensor_distance"] = s.sensor_distance;
  j["sensor_angle"] = s.sensor_angle * kDegree;
  j["move_rate"] = s.move_rate;
  j["turn_rate"] = s.turn_rate * kDegree;
  j["turn_frequency"] = s.turn_frequency;
  j["deposit_rate"] = s.deposit_rate;
  j["decay_rate"] = s.decay_rate;
  j["diffuse_rate"] = s.diffuse_rate;
  j["mean_lifetime"] = s.mean_lifetime ? nlohmann::ordered_json(*s.mean_lifetime) : nlohmann::ordered_json();
  j["activation_time"] = s.activation_time;
  j["integrator"] = s.integrator == Integrator::ForwardEuler ? "forward" : "backward";
  j["seed"] = s.seed;
  return j;
}

}  // namespace physarum
