#pragma once
// The scene the sweep tests plan (test_cli_sweep.cpp, test_sweep_on_schedulers.cpp): tiny runs (a few
// hundred agents, a few steps, a small texture), so a job takes a fraction of a second.
namespace physarum::testing {

inline constexpr const char* kTinySweepScene = R"({
  "mesh": "shape:sphere", "scale_to_area": 1.0, "agents": 200, "time_step": 0.01,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3
})";
inline constexpr const char* kTinySweepRunOptions = " --steps 4 --backend reference --texture-size 16";

}  // namespace physarum::testing
