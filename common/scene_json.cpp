#include "common/scene_json.hpp"

#include <cmath>

namespace physarum {

nlohmann::ordered_json scene_parameters_json(const Scene& s) {
  nlohmann::ordered_json j;
  j["mesh"] = s.mesh;
  j["scale_to_area"] = s.scale_to_area ? nlohmann::ordered_json(*s.scale_to_area) : nlohmann::ordered_json();
  j["max_circumradius"] = s.max_circumradius ? nlohmann::ordered_json(*s.max_circumradius) : nlohmann::ordered_json();
  j["min_angle"] = s.min_angle_deg;
  j["agents"] = s.agents;
  j["time_step"] = s.time_step;
  for (const ParameterSpec& p : kParameterTable) {
    const double value = s.parameters[p.id];
    j[std::string(p.key)] = p.null_means_infinite && std::isinf(value) ? nlohmann::ordered_json()
                                                                        : nlohmann::ordered_json(to_file_units(p, value));
  }
  j["integrator"] = s.integrator == Integrator::ForwardEuler ? "forward" : "backward";
  j["seed"] = s.seed;
  return j;
}

}  // namespace physarum
