#pragma once
// The model's parameters (Table 1 of the paper), described ONCE. Everything else is derived from
// kParameterTable: the scene file's keys, their checks and error messages (common/scene/scene.cpp),
// the per-vertex storage (common/model/vertex_parameters.hpp), the record the OpenCL kernels read and its
// interpolation (opencl/agent_parameters.cpp generates the kernels' struct from this table),
// run.json's "parameters" (common/scene/scene_json.cpp) and the README's table of scene keys (checked
// against this table by tests/test_parameter_table.cpp).
//
// Adding a parameter: one enumerator, one row of the table, and the code that uses it.
#include "common/base/value_range.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace physarum {

// Indices into the table; the order is the table's, the scene file's and run.json's.
enum class Param : int {
  sensor_distance,
  sensor_angle,
  move_rate,
  turn_rate,
  turn_frequency,
  deposit_rate,
  decay_rate,
  diffuse_rate,
  mean_lifetime,
  activation_time,
};
inline constexpr std::size_t kParamCount = 10;

// Who reads a parameter, and so how a spatially varying value is interpolated.
enum class ParamUser {
  Agent,  // read at an agent's position: barycentric interpolation of the three corner values
  Field,  // read per vertex by the field model (the diagonals R_dif, R_dec of Eq. 6/7)
};

// How the OpenCL kernels receive an agent parameter.
enum class DeviceForm {
  Value,       // as it is (float)
  Reciprocal,  // 1/value, 0 for +infinity and +infinity for 0 (mean lifetime -> hazard rate)
};

struct ParameterSpec {
  Param id;
  std::string_view key;   // the scene key, run.json's name
  std::string_view unit;  // in the scene file
  double file_to_si;      // a file value times this is the SI value (degrees -> radians)
  ValueRange range;       // allowed values, in file units
  // nullopt: the key is required (its value changes the pattern, so no silent default).
  std::optional<double> default_value;
  // null in the file means +infinity (mean_lifetime: no turnover); the key is still required, so
  // "no turnover" is always a choice.
  bool null_means_infinite;
  bool spatial;  // may vary over the surface (stored per vertex)
  ParamUser user;
  std::string_view device_name;  // the field of the kernels' record (agent parameters only)
  DeviceForm device_form;
  std::string_view doc;  // one line for the README
};

inline constexpr double kDegree = 3.14159265358979323846 / 180.0;

// THE table. Ranges: r_dec > 0 because the steady state U (Eq. 5) divides by it (without decay the
// pheromone grows forever); sensor angles may be negative (chemo-repulsion, Fig. 9c).
inline constexpr std::array<ParameterSpec, kParamCount> kParameterTable = {{
    {Param::sensor_distance, "sensor_distance", "m", 1.0, kPositive, std::nullopt, false, true, ParamUser::Agent,
     "sensor_distance", DeviceForm::Value, "distance d from an agent to its sensors"},
    {Param::sensor_angle, "sensor_angle", "deg", kDegree, ValueRange{-180.0, false, 180.0, false}, std::nullopt, false,
     true, ParamUser::Agent, "sensor_angle", DeviceForm::Value,
     "angle theta of the side sensors from the heading; negative = chemo-repulsion"},
    {Param::move_rate, "move_rate", "m/s", 1.0, kNonNegative, std::nullopt, false, true, ParamUser::Agent, "move_rate",
     DeviceForm::Value, "speed v of an agent along its heading"},
    {Param::turn_rate, "turn_rate", "deg/s", kDegree, kNonNegative, std::nullopt, false, true, ParamUser::Agent,
     "turn_rate", DeviceForm::Value, "turn rate omega, integrated over each turn-decision period"},
    {Param::turn_frequency, "turn_frequency", "1/s", 1.0, kPositive, std::nullopt, false, true, ParamUser::Agent,
     "turn_frequency", DeviceForm::Value, "turn decisions per second f_i"},
    {Param::deposit_rate, "deposit_rate", "amount/s", 1.0, kNonNegative, std::nullopt, false, true, ParamUser::Agent,
     "deposit_rate", DeviceForm::Value, "pheromone r_dep an active agent deposits per second, along its path"},
    {Param::decay_rate, "decay_rate", "1/s", 1.0, kPositive, std::nullopt, false, true, ParamUser::Field, "",
     DeviceForm::Value, "decay rate r_dec of the pheromone (diagonal of R_dec)"},
    {Param::diffuse_rate, "diffuse_rate", "m^2/s", 1.0, kNonNegative, std::nullopt, false, true, ParamUser::Field, "",
     DeviceForm::Value, "diffusion coefficient r_dif of the pheromone (diagonal of R_dif)"},
    {Param::mean_lifetime, "mean_lifetime", "s", 1.0, kPositive, std::nullopt, true, true, ParamUser::Agent,
     "hazard_rate", DeviceForm::Reciprocal, "mean agent lifetime tau (turnover); null = no turnover"},
    {Param::activation_time, "activation_time", "s", 1.0, kNonNegative, 0.0, false, true, ParamUser::Agent,
     "activation_time", DeviceForm::Value, "age t_a before a newborn agent deposits"},
}};

static_assert([] {
  for (std::size_t i = 0; i < kParamCount; ++i)
    if (static_cast<std::size_t>(kParameterTable[i].id) != i) return false;
  return true;
}(), "kParameterTable: rows must be in the order of enum Param");

constexpr const ParameterSpec& parameter_spec(Param p) { return kParameterTable[static_cast<std::size_t>(p)]; }

// The values a parameter MAP may take, in file units: the parameter's own range, except that a mean
// lifetime map may be 0 where it makes a sink (Sec. 3.3: agents there are removed at once and respawn
// elsewhere). A constant lifetime of 0 would remove every agent every step, so the number stays > 0.
constexpr ValueRange map_value_range(const ParameterSpec& spec) {
  return spec.id == Param::mean_lifetime ? kNonNegative : spec.range;
}

// The agent parameters, in table order: the fields of the kernels' record, in this order.
inline constexpr std::size_t kAgentParamCount = [] {
  std::size_t n = 0;
  for (const ParameterSpec& s : kParameterTable) n += s.user == ParamUser::Agent ? 1 : 0;
  return n;
}();
inline constexpr std::array<Param, kAgentParamCount> kAgentParams = [] {
  std::array<Param, kAgentParamCount> a{};
  std::size_t n = 0;
  for (const ParameterSpec& s : kParameterTable)
    if (s.user == ParamUser::Agent) a[n++] = s.id;
  return a;
}();

// An SI value in the scene file's units, as run.json shows it. Degrees are computed as
// radians * (180 / pi), the form stored harness statistics were written with.
double to_file_units(const ParameterSpec& spec, double si_value);

// What the device record holds for a parameter's SI value (DeviceForm), in double.
double device_value(const ParameterSpec& spec, double si_value);

// One value per parameter, in SI units (radians, 1/s, ...; +infinity for a null mean_lifetime).
class ParameterValues {
 public:
  double& operator[](Param p) { return values_[static_cast<std::size_t>(p)]; }
  double operator[](Param p) const { return values_[static_cast<std::size_t>(p)]; }
  bool operator==(const ParameterValues&) const = default;

 private:
  std::array<double, kParamCount> values_{};
};

}  // namespace physarum
