// The host factorization behind the OpenCL backend's implicit solves (opencl/host_cholesky_solve.hpp)
// against known answers: S x = b for an x chosen first (b = S x computed in double), at both
// precisions, in place and not, in each of the factor's layouts; an indefinite S refused at both; and the automatic placement of
// the solve (every size on a CPU device).
#include "common/base/errors.hpp"
#include "opencl/host_cholesky_solve.hpp"
#include "opencl/runtime/compute_context.hpp"

#include <gtest/gtest.h>

#include <limits>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <cmath>
#include <utility>
#include <vector>

namespace physarum::opencl {
namespace {

// The 1-D mass + dt * stiffness of a ring of n nodes: 1 + 2a on the diagonal, -a to either side.
// Symmetric positive definite for a > -1/4 (its eigenvalues are 1 + 2a (1 - cos θ) in [1, 1 + 4a]);
// indefinite below. The ring's wrap-around entries give the factor fill, so the ordering matters.
CsrMatrix ring(int n, double a) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> m(n, n);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 1.0 + 2.0 * a);
    t.emplace_back(i, (i + 1) % n, -a);
    t.emplace_back(i, (i + n - 1) % n, -a);
  }
  m.setFromTriplets(t.begin(), t.end());
  return CsrMatrix::from_eigen(m);
}

TEST(HostCholeskySolve, SolvesAKnownSystemAtBothPrecisions) {
  const int n = 500;
  const double a = 20.0;  // condition number 1 + 4a = 81
  const CsrMatrix S = ring(n, a);
  std::vector<double> x(static_cast<size_t>(n)), b;
  for (int i = 0; i < n; ++i) x[static_cast<size_t>(i)] = std::sin(0.37 * i) + 0.5;
  S.multiply(x, b);
  const std::vector<float> bf(b.begin(), b.end());
  for (const FactorPrecision precision : {FactorPrecision::Single, FactorPrecision::Double}) {
    HostCholeskySolve solve(S, precision, "test ring");
    ASSERT_EQ(solve.size(), n);
    std::vector<float> out(static_cast<size_t>(n), -1.0f), in_place = bf;
    solve.solve(bf.data(), out.data());
    solve.solve(in_place.data(), in_place.data());
    // float: b itself is rounded (1 ulp ~ 6e-8 relative), amplified at most by the condition
    // number, plus the factor's own rounding; double: only the final rounding of x to float.
    const double tolerance = precision == FactorPrecision::Single ? 81 * 6e-7 : 81 * 6e-8;
    for (int i = 0; i < n; ++i) {
      const size_t k = static_cast<size_t>(i);
      ASSERT_NEAR(out[k], x[k], tolerance) << (precision == FactorPrecision::Single ? "float" : "double") << " row " << i;
      ASSERT_EQ(in_place[k], out[k]) << "in place, row " << i;
    }
  }
}

// A decayed field's tails below float's smallest normal number (1.2e-38) are solved as zeros
// (opencl/runtime/flush_denormals.hpp: denormal arithmetic is ~2x slower on x86), and the caller's
// floating-point mode is left as it was.
// A surface-like system: a g x g grid where every node couples to its eight neighbours with weights
// in [0.5, 2], S = (1 + row sum) I - W, symmetric and diagonally dominant (eigenvalues in [1, 1 + 2
// max row sum], condition number below 33). Its factor fills in: lines of L run from a few entries
// to dozens, so the sweeps' four-way sums and their remainders are all exercised, unlike the ring's
// two-entry lines.
CsrMatrix weighted_grid(int g) {
  const int n = g * g;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> row_sum(static_cast<size_t>(n), 0.0);
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x)
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{1, -1}}) {
        const int x2 = x + dx, y2 = y + dy;
        if (x2 < 0 || x2 >= g || y2 < 0 || y2 >= g) continue;
        const int a = y * g + x, b = y2 * g + x2;
        const double w = 0.5 + 1.5 * std::fabs(std::sin(0.7 * a + 1.3 * b));
        t.emplace_back(a, b, -w);
        t.emplace_back(b, a, -w);
        row_sum[static_cast<size_t>(a)] += w;
        row_sum[static_cast<size_t>(b)] += w;
      }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 1.0 + row_sum[static_cast<size_t>(i)]);
  Eigen::SparseMatrix<double, Eigen::RowMajor> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return CsrMatrix::from_eigen(m);
}

TEST(HostCholeskySolve, SolvesASystemWhoseFactorFillsInAtBothPrecisions) {
  const int g = 40;
  const CsrMatrix S = weighted_grid(g);
  const int n = S.rows;
  std::vector<double> x(static_cast<size_t>(n)), b;
  for (int i = 0; i < n; ++i) x[static_cast<size_t>(i)] = std::cos(0.11 * i) + 1.5;  // in [0.5, 2.5]
  S.multiply(x, b);
  const std::vector<float> bf(b.begin(), b.end());
  // The three layouts: L D L^T with the forward sweep along L's rows (a small factor's copy by
  // rows) or down its columns (a larger factor's, forced here with no room for the copy), and the
  // supernodal L L^T of large systems (forced here at any size).
  enum Layout { kByRows, kByColumns, kSupernodal };
  for (const Layout layout : {kByRows, kByColumns, kSupernodal})
    for (const FactorPrecision precision : {FactorPrecision::Single, FactorPrecision::Double}) {
      HostCholeskySolve solve(S, precision, "test grid", layout == kByRows ? kMaxRowCopyBytes : 0,
                              layout == kSupernodal ? 0 : n + 1);
      std::vector<float> out(static_cast<size_t>(n), -1.0f), in_place = bf;
      solve.solve(bf.data(), out.data());
      solve.solve(in_place.data(), in_place.data());
      // As above, with the condition number's bound 33 (and |x| <= 2.5): float ~ 33 * 2.5 * 6e-7,
      // double only the rounding of b and of x to float.
      const double tolerance = precision == FactorPrecision::Single ? 33 * 2.5 * 6e-7 : 33 * 2.5 * 6e-8;
      const char* name = layout == kByRows ? " by rows" : layout == kByColumns ? " by columns" : " supernodal";
      for (int i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(i);
        ASSERT_NEAR(out[k], x[k], tolerance) << (precision == FactorPrecision::Single ? "float" : "double") << name
                                             << ", row " << i;
        ASSERT_EQ(in_place[k], out[k]) << "in place" << name << ", row " << i;
      }
    }
}

TEST(HostCholeskySolve, FlushesDenormalRightHandSidesToZeroAndRestoresTheMode) {
#if defined(__SSE__)
  const CsrMatrix S = ring(50, 2.0);
  std::vector<float> b(50, 1e-40f), x(50, -1.0f);  // denormal floats
  ASSERT_GT(b[0], 0.0f);
  ASSERT_LT(b[0], std::numeric_limits<float>::min());
  const unsigned mode = _mm_getcsr();
  for (const FactorPrecision precision : {FactorPrecision::Single, FactorPrecision::Double}) {
    HostCholeskySolve(S, precision, "test ring").solve(b.data(), x.data());
    for (const float v : x) ASSERT_EQ(v, 0.0f) << (precision == FactorPrecision::Single ? "float" : "double");
    EXPECT_EQ(_mm_getcsr(), mode);
  }
  volatile float tiny = 1e-38f;
  EXPECT_GT(tiny * 0.01f, 0.0f) << "denormals still flushed after the solve";
#else
  GTEST_SKIP() << "the flush is checked on x86 only";
#endif
}

TEST(HostCholeskySolve, RefusesAnIndefiniteSystemNamingIt) {
  const CsrMatrix S = ring(40, -0.3);  // eigenvalues down to 1 - 1.2 < 0
  for (const int min_supernodal_rows : {kMinSupernodalRows, 0})
    for (const FactorPrecision precision : {FactorPrecision::Single, FactorPrecision::Double}) {
      try {
        HostCholeskySolve solve(S, precision, "the test's ring", kMaxRowCopyBytes, min_supernodal_rows);
        FAIL() << "an indefinite system was factored" << (min_supernodal_rows ? "" : " (supernodal)");
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the test's ring"), std::string::npos) << e.what();
      }
    }
}

TEST(HostCholeskySolve, AutomaticPlacementSolvesEverySizeOnTheHostOfACpuDevice) {
  const ComputeContext compute = make_compute_context("");
  const DeviceInfo& device = compute.device;
  if (device.type != "CPU") GTEST_SKIP() << "the device is not a CPU: " << device.describe();
  for (const int n : {1000, 1000000, 100000000}) EXPECT_TRUE(implicit_solve_on_host(device, n)) << n;
}

}  // namespace
}  // namespace physarum::opencl
