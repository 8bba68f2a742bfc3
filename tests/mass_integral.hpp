#pragma once
// The lumped-mass integral of a vertex field, sum_i m_i u_i, computed here in the plainest way so
// that the tests of conservation do not take it from the code under test.
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"

namespace physarum::testing {

inline double mass_integral(const SurfaceDomain& d, const IntrinsicVertexData<double>& u) {
  double sum = 0.0;
  for (int v = 0; v < d.vertex_count; ++v) sum += d.vertex_mass[v] * u[v];
  return sum;
}

}  // namespace physarum::testing
