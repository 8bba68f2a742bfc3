// Newton's method on the thin shell (common/shell/shell_equilibrium.hpp) against known shapes: a
// uniformly grown disk stays flat and unstressed with its radius scaled; a disk grown into the
// metric of a spherical cap takes that cap's Gaussian and mean curvature, into a hyperbolic metric a
// saddle; the residual falls quadratically at the end; the same seed gives the same bits.
#include "common/mesh/mesh_loading.hpp"
#include "common/shell/hinge_bending.hpp"
#include "common/shell/rest_metric.hpp"
#include "common/shell/sheet_perturbation.hpp"
#include "common/shell/shell_equilibrium.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace physarum {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct GrownDisk {
  ShellTopology topology;
  std::vector<Eigen::Vector3d> initial;
  std::vector<Eigen::Vector3d> positions;
  std::vector<NewtonReport> reports;
};

// The unit disk (817 vertices) grown isotropically by stretch(rho) (rho: a face centroid's initial
// distance from the centre) in `steps` equal steps, each solved from the last with a tiny seeded
// out-of-plane nudge first.
GrownDisk grow_disk(const std::function<double(double)>& stretch, const ShellMaterial& material, int steps,
                    std::uint32_t seed = 1) {
  const InputMesh disk = load_mesh("shape:disk");
  GrownDisk grown{build_shell_topology(disk.vertex_count(), disk.triangles), disk.positions, disk.positions, {}};
  const ShellRestState initial = rest_state_of(grown.topology, disk.positions);
  const ShellEquilibrium solver(grown.topology, material, central_face(grown.topology, disk.positions));
  for (int step = 1; step <= steps; ++step) {
    ShellRestState rest = initial;
    for (std::size_t f = 0; f < rest.face_metric.size(); ++f) {
      const auto& t = grown.topology.faces[f];
      const double rho = ((disk.positions[t[0]] + disk.positions[t[1]] + disk.positions[t[2]]) / 3.0).norm();
      const double s = 1.0 + (stretch(rho) - 1.0) * step / steps;
      rest.face_metric[f] *= s * s;
    }
    perturb_out_of_plane(grown.topology, grown.positions, 1e-4, seed, static_cast<std::uint32_t>(step));
    grown.reports.push_back(solver.solve(grown.positions, rest, NewtonSettings{}));
    EXPECT_TRUE(grown.reports.back().converged) << "growth step " << step << ": residual " << grown.reports.back().residual();
  }
  return grown;
}

// Angle defect over a third of the incident area (Gaussian curvature) and a quarter of the incident
// edges' |e| |theta| over the same area (|mean curvature|), summed over the interior vertices whose
// initial radius is below `within`: the area-weighted averages.
struct Curvatures {
  double gaussian = 0.0, mean = 0.0;
};
Curvatures interior_curvatures(const GrownDisk& g, double within) {
  const std::size_t n = g.positions.size();
  std::vector<double> angle(n, 0.0), area(n, 0.0), bend(n, 0.0);
  for (const auto& t : g.topology.faces) {
    const Eigen::Vector3d p[3] = {g.positions[t[0]], g.positions[t[1]], g.positions[t[2]]};
    const double a = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
      angle[t[c]] += std::atan2(u.cross(v).norm(), u.dot(v));
      area[t[c]] += a / 3.0;
    }
  }
  for (const ShellHinge& h : g.topology.hinges) {
    const auto& v = h.vertices;
    const double theta = dihedral_angle(g.positions[v[0]], g.positions[v[1]], g.positions[v[2]], g.positions[v[3]]);
    const double weight = 0.25 * (g.positions[v[1]] - g.positions[v[0]]).norm() * theta;
    bend[v[0]] += weight;
    bend[v[1]] += weight;
  }
  double defect = 0.0, bending = 0.0, total_area = 0.0;
  for (std::size_t v = 0; v < n; ++v) {
    if (g.topology.on_boundary[v] || g.initial[v].norm() >= within) continue;
    defect += 2 * kPi - angle[v];
    bending += bend[v];
    total_area += area[v];
  }
  return {defect / total_area, std::abs(bending) / total_area};
}

TEST(ShellEquilibrium, UniformGrowthKeepsTheDiskFlatAndScalesItsRadius) {
  const double factor = 1.3;
  const GrownDisk g = grow_disk([&](double) { return factor; }, {0.01, 1e7, 0.3}, 3);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : g.positions) centre += p;
  centre /= static_cast<double>(g.positions.size());
  // Flat: every vertex within 1e-6 of the plane through the centre with the sheet's normal.
  const Eigen::Vector3d normal = vertex_normals(g.topology, g.positions)[0];
  double flatness = 0.0, radius_error = 0.0;
  for (std::size_t v = 0; v < g.positions.size(); ++v) {
    flatness = std::max(flatness, std::abs((g.positions[v] - centre).dot(normal)));
    radius_error = std::max(radius_error, std::abs((g.positions[v] - centre).norm() - factor * g.initial[v].norm()));
  }
  EXPECT_LT(flatness, 1e-6);
  EXPECT_LT(radius_error, 1e-6);
  EXPECT_LT(g.reports.back().energy.total(), 1e-12 * 1e7 * 0.01);
}

TEST(ShellEquilibrium, ASphericalCapMetricGivesTheCapsCurvature) {
  // The conformal factor 1 / (1 + k rho^2 / 4) has Gaussian curvature k (stereographic projection).
  // Scaled by c = 1 + k / 4 so that the rim keeps its length, the metric has curvature k / c^2 (a
  // metric scaled by c^2 has its curvature divided by c^2): a cap of radius c / sqrt(k).
  const double k = 1.0, c = 1 + k / 4, curvature = k / (c * c);
  const auto stretch = [&](double rho) { return c / (1 + k * rho * rho / 4); };
  const GrownDisk g = grow_disk(stretch, {0.002, 1e7, 0.3}, 8);
  const Curvatures measured = interior_curvatures(g, 0.7);
  EXPECT_NEAR(measured.gaussian, curvature, 0.1 * curvature);
  EXPECT_NEAR(measured.mean, std::sqrt(curvature), 0.1 * std::sqrt(curvature));
  // Newton's convergence is quadratic at the end: the computational order
  // log(r[i+1] / r[i]) / log(r[i] / r[i-1]) over the last three residuals is near 2 (1 for a
  // linearly converging method).
  const std::vector<double>& r = g.reports.back().residuals;
  ASSERT_GE(r.size(), 4u);
  const std::size_t n = r.size() - 1;
  const double order = std::log(r[n] / r[n - 1]) / std::log(r[n - 1] / r[n - 2]);
  EXPECT_GT(order, 1.8) << "residuals " << r[n - 2] << ", " << r[n - 1] << ", " << r[n];
}

TEST(ShellEquilibrium, AHyperbolicMetricGivesASaddle) {
  const double k = -1.0;
  const auto stretch = [&](double rho) { return 1 / (1 + k * rho * rho / 4); };
  const GrownDisk g = grow_disk(stretch, {0.002, 1e7, 0.3}, 8);
  const Curvatures c = interior_curvatures(g, 0.7);
  EXPECT_NEAR(c.gaussian, k, 0.1 * std::abs(k));
}

TEST(ShellEquilibrium, TheSameSeedGivesTheSameBits) {
  const auto stretch = [](double rho) { return 1.2 - 0.2 * rho; };
  const GrownDisk a = grow_disk(stretch, {0.005, 1e7, 0.3}, 2, 9);
  const GrownDisk b = grow_disk(stretch, {0.005, 1e7, 0.3}, 2, 9);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t v = 0; v < a.positions.size(); ++v) ASSERT_EQ(a.positions[v], b.positions[v]) << "vertex " << v;
}

}  // namespace
}  // namespace physarum
