#pragma once
// The sheet's total elastic energy (membrane on every face + bending on every interior edge), its
// gradient and its Hessian in the 3n coordinates of the n vertices (vertex v's x, y, z at 3v..3v+2).
// Elements are evaluated in parallel into their own slots and summed in element order, so every
// result is the same bits whatever the number of threads.
#include "common/shell/rest_metric.hpp"
#include "common/shell/shell_material.hpp"
#include "common/shell/shell_topology.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace physarum {

struct ShellEnergyParts {
  double membrane = 0.0;
  double bending = 0.0;
  double total() const { return membrane + bending; }
};

class ShellEnergy {
 public:
  ShellEnergy(const ShellTopology& topology, const ShellMaterial& material);

  const ShellTopology& topology() const { return topology_; }
  const ShellMaterial& material() const { return material_; }

  ShellEnergyParts energy(const Eigen::VectorXd& x, const ShellRestState& rest) const;
  Eigen::VectorXd gradient(const Eigen::VectorXd& x, const ShellRestState& rest) const;
  // The Hessian's values on pattern() (same sparsity every call: CHOLMOD analyses it once). With
  // `project`, each element's Hessian is first made positive semidefinite
  // (common/numerics/positive_projection.hpp), so the sum is too.
  void hessian(const Eigen::VectorXd& x, const ShellRestState& rest, bool project,
               Eigen::SparseMatrix<double>& out) const;
  // The sparsity of the Hessian: the 3 x 3 blocks of every pair of vertices sharing a face or a
  // hinge, both triangles stored, values zero.
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }

 private:
  ShellTopology topology_;
  ShellMaterial material_;
  Eigen::SparseMatrix<double> pattern_;
  // For each element (faces first, then hinges), for each (row corner, column corner, column
  // component) the offset in pattern_'s values of the block's first row: the block's three rows
  // follow it.
  std::vector<int> face_offsets_;   // 3 * 3 * 3 per face
  std::vector<int> hinge_offsets_;  // 4 * 4 * 3 per hinge
};

// Positions as the solver's coordinate vector and back.
Eigen::VectorXd to_coordinates(const std::vector<Eigen::Vector3d>& positions);
std::vector<Eigen::Vector3d> to_positions(const Eigen::VectorXd& x);

}  // namespace physarum
