// The thin shell's energies (common/shell/): gradients and Hessians against finite differences,
// the dihedral angle against known folds, the bending weight against the plate energy of a bent
// cylinder, and the topology's refusals.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/numerics/positive_projection.hpp"
#include "common/shell/hinge_bending.hpp"
#include "common/shell/membrane_energy.hpp"
#include "common/shell/rest_metric.hpp"
#include "common/shell/shell_energy.hpp"
#include "common/shell/shell_material.hpp"
#include "common/shell/shell_topology.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace physarum {
namespace {


// Central differences of f at x, step h: the gradient.
Eigen::VectorXd numeric_gradient(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                                 double h) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x, minus = x;
    plus(i) += h;
    minus(i) -= h;
    g(i) = (f(plus) - f(minus)) / (2 * h);
  }
  return g;
}

// Central differences of the gradient: the Hessian, column by column.
Eigen::MatrixXd numeric_hessian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& grad,
                                const Eigen::VectorXd& x, double h) {
  Eigen::MatrixXd hessian(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x, minus = x;
    plus(i) += h;
    minus(i) -= h;
    hessian.col(i) = (grad(plus) - grad(minus)) / (2 * h);
  }
  return hessian;
}

double relative_error(const Eigen::MatrixXd& value, const Eigen::MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

Eigen::Vector3d corner(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

ShellMaterial steel_sheet() { return {0.01, 2e11, 0.3}; }

TEST(ShellMembrane, GradientAndHessianMatchFiniteDifferencesOnRandomTriangles) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const ShellMaterial material = steel_sheet();
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(9), rest_shape(9);
    for (int i = 0; i < 9; ++i) x(i) = uniform(random), rest_shape(i) = uniform(random);
    const Eigen::Matrix2d rest = triangle_metric(corner(rest_shape, 0), corner(rest_shape, 1), corner(rest_shape, 2));
    if (metric_area(rest) < 0.05) continue;  // keep the rest triangle well shaped
    const auto energy = [&](const Eigen::VectorXd& p) {
      return membrane_energy(corner(p, 0), corner(p, 1), corner(p, 2), rest, material);
    };
    const auto gradient = [&](const Eigen::VectorXd& p) -> Eigen::VectorXd {
      return membrane_element(corner(p, 0), corner(p, 1), corner(p, 2), rest, material, false).gradient;
    };
    const MembraneElement element = membrane_element(corner(x, 0), corner(x, 1), corner(x, 2), rest, material, true);
    EXPECT_DOUBLE_EQ(element.energy, energy(x));
    EXPECT_LT(relative_error(element.gradient, numeric_gradient(energy, x, 1e-6)), 1e-6) << "trial " << trial;
    EXPECT_LT(relative_error(element.hessian, numeric_hessian(gradient, x, 1e-6)), 1e-4) << "trial " << trial;
  }
}

TEST(ShellMembrane, RestAndRigidMotionsCostNothingAndStretchingCostsTheContinuumValue) {
  const ShellMaterial material = steel_sheet();
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Eigen::Matrix2d rest = triangle_metric(a, b, c);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(3, -2, 5);
  const MembraneElement moved =
      membrane_element(rotation * a + shift, rotation * b + shift, rotation * c + shift, rest, material, false);
  EXPECT_NEAR(moved.energy, 0.0, 1e-12 * material.membrane_stiffness());
  EXPECT_LT(moved.gradient.norm(), 1e-9 * material.membrane_stiffness());
  // A uniaxial stretch x -> (1 + s) x: Green strain E11 = ((1 + s)^2 - 1) / 2, the energy
  // Y h / (2 (1 - nu^2)) E11^2 times the area 1/2.
  const double s = 0.01, strain = ((1 + s) * (1 + s) - 1) / 2;
  const double expected = material.membrane_stiffness() / 2 * strain * strain * 0.5;
  EXPECT_NEAR(membrane_energy(a, (1 + s) * b, c, rest, material), expected, 1e-12 * expected);
}

TEST(ShellHinge, DihedralAngleOfKnownFolds) {
  const Eigen::Vector3d x0(0, 0, 0), x1(1, 0, 0);
  for (double fold : {0.0, 0.3, 1.2, 2.5, -0.8}) {
    // The second wing rotated about the edge by `fold` out of the plane, upwards (+z) for a positive
    // fold: both wings lifted fold the hinge towards the first face's normal (+z), a negative angle.
    const Eigen::Vector3d x2(0.4, 1, 0);
    const Eigen::Vector3d x3(0.6, -std::cos(fold), std::sin(fold));
    EXPECT_NEAR(dihedral_angle(x0, x1, x2, x3), -fold, 1e-12) << "fold " << fold;
  }
}

TEST(ShellHinge, GradientAndHessianMatchFiniteDifferencesOnRandomHinges) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-0.3, 0.3);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(12);
    x << 0, 0, 0, 1, 0, 0, 0.4, 1, 0, 0.5, -1, 0;
    for (int i = 0; i < 12; ++i) x(i) += uniform(random);
    const double stiffness = 2.5, rest_angle = uniform(random);
    const auto energy = [&](const Eigen::VectorXd& p) {
      return hinge_energy(corner(p, 0), corner(p, 1), corner(p, 2), corner(p, 3), stiffness, rest_angle);
    };
    const auto gradient = [&](const Eigen::VectorXd& p) -> Eigen::VectorXd {
      return hinge_element(corner(p, 0), corner(p, 1), corner(p, 2), corner(p, 3), stiffness, rest_angle, false).gradient;
    };
    const HingeElement element =
        hinge_element(corner(x, 0), corner(x, 1), corner(x, 2), corner(x, 3), stiffness, rest_angle, true);
    EXPECT_DOUBLE_EQ(element.energy, energy(x));
    EXPECT_LT(relative_error(element.gradient, numeric_gradient(energy, x, 1e-6)), 1e-6) << "trial " << trial;
    EXPECT_LT(relative_error(element.hessian, numeric_hessian(gradient, x, 1e-6)), 1e-4) << "trial " << trial;
  }
}

// The projection of an element Hessian through its non-translation part equals the textbook one,
// the whole matrix's eigen-decomposition with the negative eigenvalues zeroed (computed here with
// Eigen's dynamic-size solver), on hinges and compressed triangles whose Hessians are indefinite.
template <int N>
Eigen::MatrixXd clamped_by_full_decomposition(const Eigen::Matrix<double, N, N>& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen{Eigen::MatrixXd(m)};
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

TEST(ShellProjection, TheReducedProjectionIsTheNearestPositiveSemidefiniteMatrix) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-0.3, 0.3);
  int indefinite = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(12);
    x << 0, 0, 0, 1, 0, 0, 0.4, 1, 0, 0.5, -1, 0;
    for (int i = 0; i < 12; ++i) x(i) += uniform(random);
    Matrix12d hinge =
        hinge_element(corner(x, 0), corner(x, 1), corner(x, 2), corner(x, 3), 2.5, uniform(random), true).hessian;
    // A triangle squeezed to 0.8 of its rest size in one direction: compressive stress.
    const Eigen::Matrix2d rest = triangle_metric(corner(x, 0) / 0.8, corner(x, 1), corner(x, 2) / 0.8);
    Matrix9d membrane = membrane_element(corner(x, 0), corner(x, 1), corner(x, 2), rest, steel_sheet(), true).hessian;
    indefinite += (Eigen::SelfAdjointEigenSolver<Matrix12d>(hinge).eigenvalues().minCoeff() < 0) +
                  (Eigen::SelfAdjointEigenSolver<Matrix9d>(membrane).eigenvalues().minCoeff() < 0);
    const Eigen::MatrixXd hinge_expected = clamped_by_full_decomposition(hinge);
    const Eigen::MatrixXd membrane_expected = clamped_by_full_decomposition(membrane);
    make_positive_semidefinite<4>(hinge);
    make_positive_semidefinite<3>(membrane);
    EXPECT_LT(relative_error(hinge, hinge_expected), 1e-10) << "trial " << trial;
    EXPECT_LT(relative_error(membrane, membrane_expected), 1e-10) << "trial " << trial;
  }
  EXPECT_GE(indefinite, 20);  // the projection had work to do
}

// The disk (817 vertices) lifted onto z = f(x, y) and jiggled: a curved, irregular sheet.
std::vector<Eigen::Vector3d> curved_disk(const InputMesh& disk, double amplitude, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  std::vector<Eigen::Vector3d> p = disk.positions;
  for (Eigen::Vector3d& v : p) v += Eigen::Vector3d(uniform(random), uniform(random), 0.3 * v.x() * v.y() + uniform(random));
  return p;
}

TEST(ShellEnergyAssembly, GradientAndHessianMatchFiniteDifferencesOnACurvedSheet) {
  InputMesh disk = load_mesh("shape:disk");
  // A small patch keeps the dense finite-difference Hessian cheap: the faces within 0.3 of the centre.
  std::vector<int> keep(disk.positions.size(), -1);
  std::vector<Eigen::Vector3d> positions;
  for (std::size_t v = 0; v < disk.positions.size(); ++v)
    if (disk.positions[v].norm() < 0.3) keep[v] = static_cast<int>(positions.size()), positions.push_back(disk.positions[v]);
  std::vector<std::array<int, 3>> faces;
  for (const auto& t : disk.triangles)
    if (keep[t[0]] >= 0 && keep[t[1]] >= 0 && keep[t[2]] >= 0) faces.push_back({keep[t[0]], keep[t[1]], keep[t[2]]});
  const ShellTopology topology = build_shell_topology(static_cast<int>(positions.size()), faces);
  ASSERT_GT(topology.hinges.size(), 50u);
  const ShellRestState rest = rest_state_of(topology, positions);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-0.01, 0.01);
  Eigen::VectorXd x = to_coordinates(positions);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += uniform(random) + (i % 3 == 2 ? 0.2 * x(i - 2) * x(i - 2) : 0.0);
  const ShellEnergy shell(topology, {0.02, 1e6, 0.35});
  const auto energy = [&](const Eigen::VectorXd& p) { return shell.energy(p, rest).total(); };
  const auto gradient = [&](const Eigen::VectorXd& p) { return shell.gradient(p, rest); };
  EXPECT_LT(relative_error(shell.gradient(x, rest), numeric_gradient(energy, x, 1e-7)), 1e-6);
  Eigen::SparseMatrix<double> hessian;
  shell.hessian(x, rest, false, hessian);
  EXPECT_LT(relative_error(Eigen::MatrixXd(hessian), numeric_hessian(gradient, x, 1e-6)), 1e-4);
  // Projected, every element block is positive semidefinite, so the sum is.
  shell.hessian(x, rest, true, hessian);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen{Eigen::MatrixXd(hessian)};
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-9 * eigen.eigenvalues().maxCoeff());
}

TEST(ShellEnergyAssembly, AnUnchangedSheetHasNoEnergyAndNoForce) {
  const InputMesh disk = load_mesh("shape:disk");
  const std::vector<Eigen::Vector3d> positions = curved_disk(disk, 0.005, 5);
  const ShellTopology topology = build_shell_topology(disk.vertex_count(), disk.triangles);
  const ShellEnergy shell(topology, steel_sheet());
  const ShellRestState rest = rest_state_of(topology, positions);
  const Eigen::VectorXd x = to_coordinates(positions);
  EXPECT_NEAR(shell.energy(x, rest).total(), 0.0, 1e-20 * steel_sheet().membrane_stiffness());
  EXPECT_LT(shell.gradient(x, rest).lpNorm<Eigen::Infinity>(), 1e-12 * steel_sheet().membrane_stiffness());
}

// A patch of the equilateral lattice, edge length `edge`, 2n x 2n cells around the origin in z = 0.
struct Lattice {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int, 3>> faces;
};
Lattice equilateral_lattice(int n, double edge) {
  Lattice lattice;
  const int side = 2 * n + 1;
  for (int j = -n; j <= n; ++j)
    for (int i = -n; i <= n; ++i) lattice.positions.emplace_back(edge * (i + 0.5 * j), edge * j * std::sqrt(3.0) / 2, 0.0);
  const auto at = [&](int i, int j) { return (j + n) * side + (i + n); };
  for (int j = -n; j < n; ++j)
    for (int i = -n; i < n; ++i) {
      lattice.faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      lattice.faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return lattice;
}

TEST(ShellBending, AnEquilateralMeshBentIntoACylinderCostsThePlateEnergy) {
  // Wrapped onto a cylinder of radius R (around either in-plane axis: the edges meet it at different
  // angles), the plate energy is (D / 2) / R^2 per unit area. The patch's boundary edges carry no
  // hinge, which loses about 1 % of it here.
  const Lattice lattice = equilateral_lattice(30, 0.05);
  const ShellTopology topology = build_shell_topology(static_cast<int>(lattice.positions.size()), lattice.faces);
  const ShellRestState rest = rest_state_of(topology, lattice.positions);
  const ShellMaterial material = steel_sheet();
  const ShellEnergy shell(topology, material);
  const double radius = 4.0;
  for (int axis : {0, 1}) {
    std::vector<Eigen::Vector3d> wrapped = lattice.positions;
    for (Eigen::Vector3d& p : wrapped) {
      const double u = p(axis);
      p(axis) = radius * std::sin(u / radius);
      p.z() = radius * (1 - std::cos(u / radius));
    }
    const double bending = shell.energy(to_coordinates(wrapped), rest).bending;
    const double expected = material.bending_stiffness() / 2 / (radius * radius) * rest_area(rest);
    EXPECT_NEAR(bending, expected, 0.03 * expected) << "bent across axis " << axis;
  }
}

TEST(ShellGrowth, GrownMetricsScaleAsStated) {
  const Eigen::Matrix2d metric = triangle_metric({0, 0, 0}, {2, 0, 0}, {0.5, 1, 0});
  EXPECT_TRUE(grown_metric(metric, 1.5, 1.5, {1, 0}).isApprox(2.25 * metric, 1e-14));
  // Along e1 by 2, across by 1: e1 doubles, e2's component along e1 doubles, the area doubles.
  const Eigen::Matrix2d grown = grown_metric(metric, 2.0, 1.0, {1, 0});
  EXPECT_NEAR(grown(0, 0), 16.0, 1e-12);
  EXPECT_NEAR(grown(0, 1), 4.0, 1e-12);                 // (4, 0) . (1, 1)
  EXPECT_NEAR(grown(1, 1), 2.0, 1e-12);                 // |(1, 1)|^2
  EXPECT_NEAR(metric_area(grown), 2 * metric_area(metric), 1e-12);
}

TEST(ShellTopologyErrors, InconsistentOrientationIsRefusedNamingTheEdge) {
  const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {0, 1, 3}};
  try {
    build_shell_topology(4, faces);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(0, 1)"), std::string::npos) << e.what();
  }
}

TEST(ShellMaterialErrors, OutOfRangeValuesAreRefusedNamingTheKey) {
  const auto message = [](const ShellMaterial& m) {
    try {
      validate_shell_material(m, "scene.json: shell");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({0.002, 7e10, 0.33}), "");
  EXPECT_NE(message({0.0, 7e10, 0.33}).find("thickness"), std::string::npos);
  EXPECT_NE(message({0.002, -1.0, 0.33}).find("young_modulus"), std::string::npos);
  EXPECT_NE(message({0.002, 7e10, 0.5}).find("poisson_ratio"), std::string::npos);
  EXPECT_NE(message({0.002, 7e10, -1.0}).find("poisson_ratio"), std::string::npos);
  EXPECT_NE(message({std::nan(""), 7e10, 0.3}).find("thickness"), std::string::npos);
}

}  // namespace
}  // namespace physarum
