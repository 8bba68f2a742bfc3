#pragma once
// An interval of allowed values for a scene key or a model parameter, in the units of the scene
// FILE (degrees for angles), so one description serves the file checks, the checks of a scene built
// in code and the README's table of keys.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace physarum {

struct ValueRange {
  double low = -std::numeric_limits<double>::infinity();
  bool low_open = false;  // true: value must be > low; false: >= low
  double high = std::numeric_limits<double>::infinity();
  bool high_open = false;

  bool operator==(const ValueRange&) const = default;

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (low_open ? !(v > low) : !(v >= low)) return false;
    if (high_open ? !(v < high) : !(v <= high)) return false;
    return true;
  }

  // "must be > 0", "must be in [-180, 180]", ...
  std::string describe() const {
    const bool has_low = std::isfinite(low), has_high = std::isfinite(high);
    if (has_low && has_high)
      return "must be in " + std::string(low_open ? "(" : "[") + number(low) + ", " + number(high) +
             (high_open ? ")" : "]");
    if (has_low) return "must be " + std::string(low_open ? "> " : ">= ") + number(low);
    if (has_high) return "must be " + std::string(high_open ? "< " : "<= ") + number(high);
    return "must be a finite number";
  }

  // A value as a scene file would show it (no trailing zeros, no fixed six decimals).
  static std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", x);
    return buf;
  }
};

inline constexpr ValueRange kPositive{0.0, true};
inline constexpr ValueRange kNonNegative{0.0, false};

}  // namespace physarum
