#include "common/growth/growth_law.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

double growth_increment(const GrowthLaw& law, double a, double b) {
  const double term = std::pow(std::max(a, 0.0), law.m) * std::pow(std::max(b, 0.0), law.n) / law.gamma;
  return law.function == GrowthFunction::Polynomial ? term : law.lambda * std::exp(term - 1.0);
}

double growth_stretch(const GrowthLaw& law, double a, double b) { return 1.0 + law.rate * growth_increment(law, a, b); }

void validate_growth_law(const GrowthLaw& law, const std::string& where) {
  const auto require = [&](bool ok, const char* key, double value, const char* what) {
    if (!ok) throw InputError(where + ": \"" + key + "\" must be " + what + ", got " + std::to_string(value));
  };
  require(std::isfinite(law.gamma) && law.gamma > 0.0, "gamma", law.gamma, "a positive number");
  require(std::isfinite(law.lambda) && law.lambda > 0.0, "lambda", law.lambda, "a positive number");
  require(std::isfinite(law.rate) && law.rate > 0.0, "rate", law.rate, "a positive number");
  require(std::isfinite(law.m) && law.m >= 0.0, "m", law.m, "a number >= 0");
  require(std::isfinite(law.n) && law.n >= 0.0, "n", law.n, "a number >= 0");
}

}  // namespace physarum
