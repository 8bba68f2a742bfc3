#include "common/intrinsic/refinement_estimate.hpp"

#include "common/base/errors.hpp"
#include "common/base/number_format.hpp"

#include <algorithm>
#include <cmath>

namespace physarum {

std::string RefinementEstimate::describe() const {
  return "physarum: refining " + format_number(area) + " m^2 to max circumradius " + format_number(max_circumradius) +
         " m: about " + format_number(std::round(vertices)) + " intrinsic vertices (estimate); this may take a while";
}

RefinementEstimate estimate_refinement(double area, int current_vertices, const RefinementOptions& options) {
  RefinementEstimate e;
  e.area = area;
  e.max_circumradius = options.max_circumradius;
  e.budget = options.max_insertions;
  e.vertices = current_vertices;
  if (std::isfinite(options.max_circumradius) && options.max_circumradius > 0.0) {
    const double face_area = 3.0 * std::sqrt(3.0) / 4.0 * options.max_circumradius * options.max_circumradius;
    e.vertices = std::max<double>(current_vertices, area / face_area / 2.0);
  }
  e.insertions = e.vertices - current_vertices;
  return e;
}

RefinementEstimate check_refinement_size(const std::string& source, double area, int current_vertices,
                                         const RefinementOptions& options) {
  const RefinementEstimate e = estimate_refinement(area, current_vertices, options);
  if (e.insertions > static_cast<double>(e.budget))
    throw InputError("refusing " + (source.empty() ? std::string("the scene") : source) + ": refining " + format_number(area) + " m^2 to max circumradius " +
                    format_number(e.max_circumradius) + " m needs about " + format_number(e.insertions) +
                    " vertex insertions (estimated from the area: a face of circumradius R covers at most " +
                    "1.3 R^2), more than the refinement's budget of " + format_number(static_cast<double>(e.budget)) +
                    "; use a max_circumradius of at least " +
                    format_number(std::sqrt(area / (2.0 * static_cast<double>(e.budget)) / (3.0 * std::sqrt(3.0) / 4.0))) +
                    " m");
  return e;
}

}  // namespace physarum
