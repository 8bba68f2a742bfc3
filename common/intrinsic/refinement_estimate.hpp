#pragma once
// How big a refinement will be, known before it starts: the bound a scene asks for is refused when
// it would exceed the refinement's insertion budget, and long refinements are announced.
#include "common/intrinsic/intrinsic_triangulation.hpp"

#include <cstddef>
#include <string>

namespace physarum {

struct RefinementEstimate {
  double area = 0.0;              // of the scaled surface
  double max_circumradius = 0.0;  // the bound (infinity when only an angle bound is given)
  double vertices = 0.0;          // estimated intrinsic vertices after refinement
  double insertions = 0.0;        // estimated insertions (vertices - the current ones)
  std::size_t budget = 0;         // RefinementOptions::max_insertions
  std::string describe() const;   // one line for stderr
};
// Refinements estimated at this many vertices or more are announced on stderr before they start.
constexpr double kRefinementNoteVertices = 200'000;

// A face with circumradius R has area at most (3 sqrt 3 / 4) R^2 (equilateral); a closed surface
// has about half as many vertices as faces. Refining to R therefore needs at least
// area / ((3 sqrt 3 / 4) R^2) / 2 vertices (a lower bound: refined faces are rarely equilateral).
RefinementEstimate estimate_refinement(double area, int current_vertices, const RefinementOptions& options);
// The estimate; InputError naming `source` when its insertions exceed options.max_insertions.
RefinementEstimate check_refinement_size(const std::string& source, double area, int current_vertices,
                                         const RefinementOptions& options);

}  // namespace physarum
