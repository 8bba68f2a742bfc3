#include "common/shell/membrane_energy.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>

namespace physarum {
namespace {

// d e_i / d x_v: e1 = x1 - x0, e2 = x2 - x0.
constexpr double kEdgeOfCorner[2][3] = {{-1.0, 1.0, 0.0}, {-1.0, 0.0, 1.0}};

// The strain measures of Delta = a - abar: with B = abar^-1, W / Abar = k ((1 - nu) tr(B Delta B Delta)
// + nu tr(B Delta)^2), k = Y h / (8 (1 - nu^2)).
struct MembraneForm {
  Eigen::Matrix2d inverse_rest;  // B
  double area;                    // Abar
  double k;
  double nu;

  double density(const Eigen::Matrix2d& delta) const {
    const Eigen::Matrix2d bd = inverse_rest * delta;
    const double trace = bd.trace();
    return k * ((1.0 - nu) * (bd * bd).trace() + nu * trace * trace);
  }
  // S with d density = tr(S d Delta).
  Eigen::Matrix2d stress(const Eigen::Matrix2d& delta) const {
    const Eigen::Matrix2d bdb = inverse_rest * delta * inverse_rest;
    return k * (2.0 * (1.0 - nu) * bdb + 2.0 * nu * (inverse_rest * delta).trace() * inverse_rest);
  }
};

MembraneForm membrane_form(const Eigen::Matrix2d& rest_metric, const ShellMaterial& material) {
  return {rest_metric.inverse(), metric_area(rest_metric), material.membrane_stiffness() / 8.0,
          material.poisson_ratio};
}

}  // namespace

Eigen::Matrix2d triangle_metric(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
  Eigen::Matrix2d a;
  a << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
  return a;
}

double metric_area(const Eigen::Matrix2d& metric) { return 0.5 * std::sqrt(std::max(metric.determinant(), 0.0)); }

double membrane_energy(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                       const Eigen::Matrix2d& rest_metric, const ShellMaterial& material) {
  const MembraneForm form = membrane_form(rest_metric, material);
  return form.area * form.density(triangle_metric(x0, x1, x2) - rest_metric);
}

MembraneElement membrane_element(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                 const Eigen::Matrix2d& rest_metric, const ShellMaterial& material,
                                 bool with_hessian) {
  const MembraneForm form = membrane_form(rest_metric, material);
  const Eigen::Matrix2d delta = triangle_metric(x0, x1, x2) - rest_metric;
  const Eigen::Matrix2d stress = form.stress(delta);
  const std::array<Eigen::Vector3d, 2> edge = {x1 - x0, x2 - x0};

  MembraneElement element;
  element.energy = form.area * form.density(delta);
  // d W / d e_i = 2 Abar sum_j S_ij e_j (a_ij = e_i . e_j).
  std::array<Eigen::Vector3d, 2> edge_gradient;
  for (int i = 0; i < 2; ++i) edge_gradient[i] = 2.0 * form.area * (stress(i, 0) * edge[0] + stress(i, 1) * edge[1]);
  for (int v = 0; v < 3; ++v)
    element.gradient.segment<3>(3 * v) = kEdgeOfCorner[0][v] * edge_gradient[0] + kEdgeOfCorner[1][v] * edge_gradient[1];
  if (!with_hessian) return element;

  // In the edge vectors: d^2 W = 2 Abar S_ij de_i . de_j  +  (d a)^T Q (d a), where a = (a11, a12, a22)
  // and Q is the Hessian of the quadratic density in them.
  const std::array<Eigen::Matrix2d, 3> unit = {(Eigen::Matrix2d() << 1, 0, 0, 0).finished(),
                                               (Eigen::Matrix2d() << 0, 1, 1, 0).finished(),
                                               (Eigen::Matrix2d() << 0, 0, 0, 1).finished()};
  Eigen::Matrix3d q;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const Eigen::Matrix2d bk = form.inverse_rest * unit[k], bl = form.inverse_rest * unit[l];
      q(k, l) = 2.0 * form.k * ((1.0 - form.nu) * (bk * bl).trace() + form.nu * bk.trace() * bl.trace());
    }
  // J: d (a11, a12, a22) / d (e1, e2), 6 x 3.
  Eigen::Matrix<double, 6, 3> jacobian = Eigen::Matrix<double, 6, 3>::Zero();
  jacobian.block<3, 1>(0, 0) = 2.0 * edge[0];
  jacobian.block<3, 1>(0, 1) = edge[1];
  jacobian.block<3, 1>(3, 1) = edge[0];
  jacobian.block<3, 1>(3, 2) = 2.0 * edge[1];
  Eigen::Matrix<double, 6, 6> edge_hessian = form.area * jacobian * q * jacobian.transpose();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) edge_hessian.block<3, 3>(3 * i, 3 * j).diagonal().array() += 2.0 * form.area * stress(i, j);
  for (int v = 0; v < 3; ++v)
    for (int w = 0; w < 3; ++w) {
      Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          block += kEdgeOfCorner[i][v] * kEdgeOfCorner[j][w] * edge_hessian.block<3, 3>(3 * i, 3 * j);
      element.hessian.block<3, 3>(3 * v, 3 * w) = block;
    }
  return element;
}

}  // namespace physarum
