#include "common/shell/shell_material.hpp"

#include "common/base/errors.hpp"

#include <cmath>

namespace physarum {

double ShellMaterial::membrane_stiffness() const {
  return young_modulus * thickness / (1.0 - poisson_ratio * poisson_ratio);
}

double ShellMaterial::bending_stiffness() const {
  return young_modulus * thickness * thickness * thickness / (12.0 * (1.0 - poisson_ratio * poisson_ratio));
}

void validate_shell_material(const ShellMaterial& material, const std::string& where) {
  const auto positive = [&](double value, const char* key) {
    if (!std::isfinite(value) || value <= 0.0)
      throw InputError(where + ": \"" + key + "\" must be a positive number, got " + std::to_string(value));
  };
  positive(material.thickness, "thickness");
  positive(material.young_modulus, "young_modulus");
  const double nu = material.poisson_ratio;
  if (!std::isfinite(nu) || nu <= -1.0 || nu >= 0.5)
    throw InputError(where + ": \"poisson_ratio\" must lie in (-1, 0.5), got " + std::to_string(nu) +
                     " (outside it the material's energy is not positive definite)");
}

}  // namespace physarum
