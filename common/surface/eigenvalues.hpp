#pragma once
// The low end of the manifold-harmonic spectrum: the smallest eigenpairs of the generalized problem
// L x = lambda M x with the cotan Laplacian L (positive semi-definite) and the diagonal lumped mass M.
#include "common/numerics/csr_matrix.hpp"
#include "common/base/element_data.hpp"

#include <Eigen/Core>
#include <vector>

namespace physarum {

struct Eigenpairs {
  Eigen::VectorXd values;   // ascending; the zero eigenvalue(s) of L included
  Eigen::MatrixXd vectors;  // column k solves L x = values[k] M x, normalised so x^T M x = 1
};

// The `count` smallest eigenvalues (and, when want_vectors, eigenvectors). count is clamped to the
// number of vertices minus one. Throws InputError when the mass has a non-positive entry or the
// solver does not converge.
Eigenpairs smallest_eigenpairs(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& mass, int count,
                               bool want_vectors = true);

// Eigenvalues only, ascending.
std::vector<double> smallest_eigenvalues(const CsrMatrix& laplacian, const IntrinsicVertexData<double>& mass, int count);

// The same for a surface domain's own Laplacian and lumped mass.
struct SurfaceDomain;
std::vector<double> smallest_eigenvalues(const SurfaceDomain& domain, int count);
Eigenpairs smallest_eigenpairs(const SurfaceDomain& domain, int count, bool want_vectors = true);

}  // namespace physarum
