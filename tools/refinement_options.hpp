#pragma once
// The intrinsic-refinement flags that `physarum mesh` and `physarum map` share (a scene file says
// the same with its keys max_circumradius and min_angle): one definition, so the two commands spell,
// check and explain them alike.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace physarum::cli {

struct RefinementFlags {
  std::optional<double> max_circumradius;      // absolute, in the units the command states
  std::optional<double> max_circumradius_rel;  // a fraction of the bounding-box diagonal
  double min_angle_deg = 0.0;                  // 0: off

  bool any() const { return max_circumradius || max_circumradius_rel || min_angle_deg > 0.0; }
  // The absolute bound for a surface of this bounding-box diagonal (the --max-circumradius-rel
  // fraction of it, or --max-circumradius); nullopt when neither was given.
  std::optional<double> absolute_max_circumradius(double bounding_box_diagonal) const {
    if (max_circumradius_rel) return *max_circumradius_rel * bounding_box_diagonal;
    return max_circumradius;
  }
};

// Adds --max-circumradius (described by `absolute_help`), --max-circumradius-rel (excluding each
// other) and --min-angle to `app`.
inline void add_refinement_flags(CLI::App* app, RefinementFlags& flags, const std::string& absolute_help) {
  auto* absolute = app->add_option("--max-circumradius", flags.max_circumradius, absolute_help)->check(CLI::PositiveNumber);
  auto* relative = app->add_option("--max-circumradius-rel", flags.max_circumradius_rel,
                                   "Like --max-circumradius, as a fraction of the bounding-box diagonal")
                       ->check(CLI::PositiveNumber);
  absolute->excludes(relative);
  app->add_option("--min-angle", flags.min_angle_deg, "Also refine faces with a smaller angle (degrees)")->check(CLI::Range(0.0, 30.0));
}

}  // namespace physarum::cli
