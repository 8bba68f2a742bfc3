#pragma once
// The elastic sheet of the growth model (paper 003): a thin shell of one isotropic, linearly elastic
// material (St. Venant-Kirchhoff), described by its thickness h, Young's modulus Y and Poisson's
// ratio nu. The membrane resists stretching with stiffness Y h / (1 - nu^2); bending with the plate's
// flexural rigidity D = Y h^3 / (12 (1 - nu^2)), so halving h makes the sheet 8 times easier to bend
// but only twice as easy to stretch: thinner sheets buckle into finer waves.
#include <string>

namespace physarum {

struct ShellMaterial {
  double thickness = 0.002;     // h, metres (the paper's aluminium sheet)
  double young_modulus = 7e10;  // Y, pascals
  double poisson_ratio = 0.33;  // nu, dimensionless, in (-1, 0.5)

  // Y h / (1 - nu^2): the plane-stress stretching stiffness, newtons per metre.
  double membrane_stiffness() const;
  // D = Y h^3 / (12 (1 - nu^2)): the flexural rigidity, newton metres.
  double bending_stiffness() const;
};

// InputError naming `where` (e.g. "scene.json: shell") when a value is not a finite positive
// thickness or modulus, or the Poisson ratio lies outside (-1, 0.5) (the range in which an isotropic
// material's energy is positive definite).
void validate_shell_material(const ShellMaterial& material, const std::string& where);

}  // namespace physarum
