#include "common/model/model_parameters.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace physarum {

double to_file_units(const ParameterSpec& spec, double si_value) {
  return spec.file_to_si == kDegree ? si_value * (180.0 / std::numbers::pi) : si_value / spec.file_to_si;
}

double device_value(const ParameterSpec& spec, double si_value) {
  switch (spec.device_form) {
    case DeviceForm::Value:
      return si_value;
    case DeviceForm::Reciprocal:
      // Interpolating the reciprocal (a hazard rate) keeps both ends finite-safe: no turnover is a
      // hazard of 0, a sink (lifetime 0) a hazard of +infinity.
      return std::isinf(si_value) ? 0.0 : (si_value > 0.0 ? 1.0 / si_value : std::numeric_limits<double>::infinity());
  }
  return si_value;
}

}  // namespace physarum
