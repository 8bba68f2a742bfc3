// The common sampling of two triangulations (common/harness/common_sampling.hpp) and the smoothing
// spectrum measured on it (common/harness/smoothing_spectrum.hpp), against known answers:
//  * a field linear in the plane is linear in every triangle of any triangulation of a flat surface,
//    so the coarse arm's field read at the fine arm's vertices is that linear function exactly;
//  * on a curved surface the reading is the coarse interpolant within the faces' sagitta;
//  * a Neumann cosine on the unit square is an eigenfunction of the Laplacian, k = 2 pi / lambda, so
//    the smoother at scale s multiplies it by 1 / (1 + (s / lambda)^2): the detail and band energies
//    are known in closed form.
#include "common/base/errors.hpp"
#include "common/harness/common_sampling.hpp"
#include "common/harness/smoothing_spectrum.hpp"
#include "common/surface/prepared_surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace physarum {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::shared_ptr<const PreparedSurface> surface(const std::string& mesh, std::optional<double> circumradius) {
  SurfaceSpec spec;
  spec.mesh = mesh;
  spec.max_circumradius = circumradius;
  return std::make_shared<const PreparedSurface>(prepare_surface(spec));
}

Eigen::Vector3d position(const PreparedSurface& s, int vertex) {
  const SurfacePoint& p = s.domain.vertex_location[static_cast<size_t>(vertex)];
  const auto& t = s.simulated.triangles[static_cast<size_t>(p.face)];
  return p.barycentric[0] * s.simulated.positions[t[0]] + p.barycentric[1] * s.simulated.positions[t[1]] +
         p.barycentric[2] * s.simulated.positions[t[2]];
}

template <class F>
Eigen::VectorXd field_on(const PreparedSurface& s, F f) {
  Eigen::VectorXd u(s.domain.vertex_count);
  for (int v = 0; v < s.domain.vertex_count; ++v) u[v] = f(position(s, v));
  return u;
}

TEST(CommonSampling, ALinearFieldOnACoarseFlatTriangulationIsReadExactlyAtTheFinerArmsVertices) {
  const auto coarse = surface("shape:square", std::nullopt), fine = surface("shape:square", 0.01);
  const CommonSampling sampling(coarse, fine);
  ASSERT_EQ(&sampling.surface(), fine.get());
  EXPECT_GT(sampling.coarser_edge_length(), 2.0 * sampling.edge_length());
  const auto linear = [](const Eigen::Vector3d& p) { return 2.0 * p.x() - 3.0 * p.y() + 5.0; };
  const Eigen::VectorXd read = CommonSampling::read(sampling.from(*coarse), field_on(*coarse, linear));
  const Eigen::VectorXd exact = field_on(*fine, linear);
  ASSERT_EQ(read.size(), exact.size());
  EXPECT_LT((read - exact).cwiseAbs().maxCoeff(), 1e-9);
  // The finer arm is read as it is.
  EXPECT_EQ(sampling.from(*fine).rows(), 0);
}

TEST(CommonSampling, OnACurvedSurfaceTheReadingIsTheCoarseInterpolantWithinTheSagitta) {
  const auto coarse = surface("shape:sphere", std::nullopt), fine = surface("shape:sphere", 0.03);
  const CommonSampling sampling(fine, coarse);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> P = sampling.from(*coarse);
  // Every row is a partition of unity over at most three coarse vertices.
  for (int r = 0; r < P.rows(); ++r) {
    double sum = 0.0;
    int entries = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(P, r); it; ++it) sum += it.value(), ++entries;
    ASSERT_NEAR(sum, 1.0, 1e-9) << "row " << r;
    ASSERT_LE(entries, 3) << "row " << r;
  }
  // z read through the coarse interpolant: within a face's sagitta h^2 / (8 R) of the exact value,
  // R = 1 (unit sphere), h the coarse mesh's longest edges (~0.1 m at level 4): ~1.3e-3.
  const auto height = [](const Eigen::Vector3d& p) { return p.z(); };
  const Eigen::VectorXd read = CommonSampling::read(P, field_on(*coarse, height));
  const Eigen::VectorXd exact = field_on(*fine, height);
  const double h = 1.5 * sampling.coarser_edge_length();
  EXPECT_LT((read - exact).cwiseAbs().maxCoeff(), h * h / 8.0);
  // Input vertices are vertices of both triangulations: read exactly.
  for (int v = 0; v < coarse->simulated.vertex_count(); ++v)
    ASSERT_NEAR(read[fine->input_to_intrinsic[static_cast<size_t>(v)]], exact[fine->input_to_intrinsic[static_cast<size_t>(v)]],
                1e-12);
}

TEST(CommonSampling, TwoDifferentSurfacesHaveNone) {
  const auto square = surface("shape:square", std::nullopt), disk = surface("shape:disk", std::nullopt);
  std::string why;
  EXPECT_FALSE(same_input_surface(*square, *disk, &why));
  EXPECT_NE(why.find("other triangles"), std::string::npos) << why;
  EXPECT_THROW(CommonSampling(square, disk), InputError);
}

TEST(SmoothingSpectrum, ANeumannCosinesDetailAndBandEnergiesHaveTheirClosedForms) {
  const auto square = surface("shape:square", 0.01);
  const double lambda = 0.25, epsilon = 0.3;
  double x0 = HUGE_VAL;  // the square's side runs from x0 to x0 + 1
  for (int v = 0; v < square->domain.vertex_count; ++v) x0 = std::min(x0, position(*square, v).x());
  const Eigen::VectorXd u =
      field_on(*square, [&](const Eigen::Vector3d& p) { return 1.0 + epsilon * std::cos(2.0 * kPi * (p.x() - x0) / lambda); });
  const std::vector<double> scales = {0.1, 0.25, 0.6};
  const SmoothingSpectrum spectrum(square->domain, scales);
  const SmoothingSpectrum::Powers p = spectrum.of(u, square->domain.total_area * 1.0 * 1.0);
  const auto kept = [&](double s) { return 1.0 / (1.0 + (s / lambda) * (s / lambda)); };  // the smoother's gain
  const double variance = epsilon * epsilon / 2.0;  // of the cosine over the unit square, mean 1
  ASSERT_EQ(p.detail.size(), 3u);
  ASSERT_EQ(p.band.size(), 2u);
  for (size_t k = 0; k < scales.size(); ++k) {
    const double expected = (1.0 - kept(scales[k])) * (1.0 - kept(scales[k])) * variance;
    EXPECT_NEAR(p.detail[k], expected, 0.03 * expected) << "detail at " << scales[k];
  }
  for (size_t k = 0; k + 1 < scales.size(); ++k) {
    const double gain = kept(scales[k]) - kept(scales[k + 1]);
    EXPECT_NEAR(p.band[k], gain * gain * variance, 0.03 * gain * gain * variance) << "band " << k;
  }
}

}  // namespace
}  // namespace physarum
