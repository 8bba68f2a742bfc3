#pragma once
// How much a piece of tissue grows in one growth step, from the morphogen concentrations on it
// (paper 003, Eqs. 6 and 7). The paper writes the increments as negative numbers (its shell code's
// sign convention for a plastic change of the rest shape); here a face GROWS by
//   stretch = 1 + rate * g(a, b)       (its rest edge lengths are multiplied by it)
// with g = -delta_s >= 0:
//   polynomial  (Eq. 7):  g = a^m b^n / gamma
//   exponential (Eq. 6):  g = lambda * exp(a^m b^n / gamma - 1)
// where a and b are the face's mean concentrations. The paper does not say how its increments enter
// the shell's time step; `rate` is that scale, stated: the relative growth per step where g = 1.
#include <string>

namespace physarum {

enum class GrowthFunction { Polynomial, Exponential };

struct GrowthLaw {
  GrowthFunction function = GrowthFunction::Polynomial;
  double m = 0.0;       // exponent of a
  double n = 1.0;       // exponent of b
  double gamma = 0.05;  // scale of the concentration term
  double lambda = 1.0;  // exponential only
  double rate = 0.01;   // relative stretch per growth step per unit of g
};

// g(a, b) >= 0 (concentrations below zero, which explicit integration can produce by rounding,
// count as zero).
double growth_increment(const GrowthLaw& law, double a, double b);

// 1 + rate * g(a, b).
double growth_stretch(const GrowthLaw& law, double a, double b);

// InputError naming `where` for a non-positive gamma, lambda or rate, or a negative exponent.
void validate_growth_law(const GrowthLaw& law, const std::string& where);

}  // namespace physarum
