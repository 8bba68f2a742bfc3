#include "common/shell/shell_energy.hpp"

#include "common/base/parallel_chunks.hpp"
#include "common/numerics/positive_projection.hpp"
#include "common/shell/hinge_bending.hpp"
#include "common/shell/membrane_energy.hpp"

#include <algorithm>

namespace physarum {
namespace {

constexpr int kChunkElements = 2048;

Eigen::Vector3d vertex(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

// D / 2: the hinge energy's factor (common/shell/hinge_bending.hpp).
double hinge_rigidity(const ShellMaterial& material) { return 0.5 * material.bending_stiffness(); }

int chunk_count(std::size_t elements) {
  return static_cast<int>((elements + kChunkElements - 1) / kChunkElements);
}

// Calls work(e) for every element, chunk by chunk in parallel.
template <typename Work>
void for_elements(std::size_t elements, const Work& work) {
  parallel_chunks(chunk_count(elements), [&](int chunk) {
    const std::size_t begin = static_cast<std::size_t>(chunk) * kChunkElements;
    const std::size_t end = std::min(elements, begin + kChunkElements);
    for (std::size_t e = begin; e < end; ++e) work(e);
  });
}

// The offsets of the 3 x 3 blocks of `corners` x `corners` in a compressed column-major matrix.
template <std::size_t N>
void append_block_offsets(const Eigen::SparseMatrix<double>& m, const std::array<int, N>& corners,
                          std::vector<int>& offsets) {
  for (std::size_t a = 0; a < N; ++a)
    for (std::size_t b = 0; b < N; ++b)
      for (int c = 0; c < 3; ++c) {
        const int column = 3 * corners[b] + c;
        const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[column];
        const int* end = m.innerIndexPtr() + m.outerIndexPtr()[column + 1];
        offsets.push_back(static_cast<int>(std::lower_bound(begin, end, 3 * corners[a]) - m.innerIndexPtr()));
      }
}

template <int N>
void scatter(const Eigen::Matrix<double, 3 * N, 3 * N>& block, const int* offsets, double* values) {
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b)
      for (int c = 0; c < 3; ++c) {
        double* column = values + offsets[(a * N + b) * 3 + c];
        for (int r = 0; r < 3; ++r) column[r] += block(3 * a + r, 3 * b + c);
      }
}

}  // namespace

Eigen::VectorXd to_coordinates(const std::vector<Eigen::Vector3d>& positions) {
  Eigen::VectorXd x(3 * static_cast<Eigen::Index>(positions.size()));
  for (std::size_t v = 0; v < positions.size(); ++v) x.segment<3>(3 * static_cast<Eigen::Index>(v)) = positions[v];
  return x;
}

std::vector<Eigen::Vector3d> to_positions(const Eigen::VectorXd& x) {
  std::vector<Eigen::Vector3d> positions(static_cast<std::size_t>(x.size() / 3));
  for (std::size_t v = 0; v < positions.size(); ++v) positions[v] = x.segment<3>(3 * static_cast<Eigen::Index>(v));
  return positions;
}

ShellEnergy::ShellEnergy(const ShellTopology& topology, const ShellMaterial& material)
    : topology_(topology), material_(material) {
  std::vector<Eigen::Triplet<double>> blocks;
  const auto couple = [&](int a, int b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) blocks.emplace_back(3 * a + r, 3 * b + c, 0.0);
  };
  for (const auto& f : topology_.faces)
    for (int a : f)
      for (int b : f) couple(a, b);
  for (const ShellHinge& h : topology_.hinges) {
    couple(h.vertices[2], h.vertices[3]);
    couple(h.vertices[3], h.vertices[2]);
  }
  const int n = 3 * topology_.vertex_count;
  pattern_.resize(n, n);
  pattern_.setFromTriplets(blocks.begin(), blocks.end());
  pattern_.makeCompressed();
  for (const auto& f : topology_.faces) append_block_offsets(pattern_, f, face_offsets_);
  for (const ShellHinge& h : topology_.hinges) append_block_offsets(pattern_, h.vertices, hinge_offsets_);
}

ShellEnergyParts ShellEnergy::energy(const Eigen::VectorXd& x, const ShellRestState& rest) const {
  const double rigidity = hinge_rigidity(material_);
  std::vector<double> membrane(topology_.faces.size()), bending(topology_.hinges.size());
  for_elements(membrane.size(), [&](std::size_t e) {
    const auto& f = topology_.faces[e];
    membrane[e] = membrane_energy(vertex(x, f[0]), vertex(x, f[1]), vertex(x, f[2]), rest.face_metric[e], material_);
  });
  for_elements(bending.size(), [&](std::size_t e) {
    const ShellHinge& h = topology_.hinges[e];
    const auto& v = h.vertices;
    bending[e] = hinge_energy(vertex(x, v[0]), vertex(x, v[1]), vertex(x, v[2]), vertex(x, v[3]),
                              rigidity * hinge_weight(h, rest), rest.hinge_angle[e]);
  });
  ShellEnergyParts parts;
  for (double e : membrane) parts.membrane += e;
  for (double e : bending) parts.bending += e;
  return parts;
}

Eigen::VectorXd ShellEnergy::gradient(const Eigen::VectorXd& x, const ShellRestState& rest) const {
  const double rigidity = hinge_rigidity(material_);
  std::vector<Vector9d> face_gradient(topology_.faces.size());
  std::vector<Vector12d> hinge_gradient(topology_.hinges.size());
  for_elements(face_gradient.size(), [&](std::size_t e) {
    const auto& f = topology_.faces[e];
    face_gradient[e] = membrane_element(vertex(x, f[0]), vertex(x, f[1]), vertex(x, f[2]), rest.face_metric[e],
                                        material_, false).gradient;
  });
  for_elements(hinge_gradient.size(), [&](std::size_t e) {
    const ShellHinge& h = topology_.hinges[e];
    const auto& v = h.vertices;
    hinge_gradient[e] = hinge_element(vertex(x, v[0]), vertex(x, v[1]), vertex(x, v[2]), vertex(x, v[3]),
                                      rigidity * hinge_weight(h, rest), rest.hinge_angle[e], false).gradient;
  });
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (std::size_t e = 0; e < face_gradient.size(); ++e)
    for (int c = 0; c < 3; ++c) g.segment<3>(3 * topology_.faces[e][c]) += face_gradient[e].segment<3>(3 * c);
  for (std::size_t e = 0; e < hinge_gradient.size(); ++e)
    for (int c = 0; c < 4; ++c) g.segment<3>(3 * topology_.hinges[e].vertices[c]) += hinge_gradient[e].segment<3>(3 * c);
  return g;
}

void ShellEnergy::hessian(const Eigen::VectorXd& x, const ShellRestState& rest, bool project,
                          Eigen::SparseMatrix<double>& out) const {
  const double rigidity = hinge_rigidity(material_);
  std::vector<Matrix9d> face_hessian(topology_.faces.size());
  std::vector<Matrix12d> hinge_hessian(topology_.hinges.size());
  for_elements(face_hessian.size(), [&](std::size_t e) {
    const auto& f = topology_.faces[e];
    face_hessian[e] = membrane_element(vertex(x, f[0]), vertex(x, f[1]), vertex(x, f[2]), rest.face_metric[e],
                                       material_, true).hessian;
    if (project) make_positive_semidefinite<3>(face_hessian[e]);
  });
  for_elements(hinge_hessian.size(), [&](std::size_t e) {
    const ShellHinge& h = topology_.hinges[e];
    const auto& v = h.vertices;
    hinge_hessian[e] = hinge_element(vertex(x, v[0]), vertex(x, v[1]), vertex(x, v[2]), vertex(x, v[3]),
                                     rigidity * hinge_weight(h, rest), rest.hinge_angle[e], true).hessian;
    if (project) make_positive_semidefinite<4>(hinge_hessian[e]);
  });
  out = pattern_;
  double* values = out.valuePtr();
  for (std::size_t e = 0; e < face_hessian.size(); ++e) scatter<3>(face_hessian[e], face_offsets_.data() + 27 * e, values);
  for (std::size_t e = 0; e < hinge_hessian.size(); ++e)
    scatter<4>(hinge_hessian[e], hinge_offsets_.data() + 48 * e, values);
}

}  // namespace physarum
