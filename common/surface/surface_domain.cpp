#include "common/surface/surface_domain.hpp"

#include "common/base/errors.hpp"
#include "common/surface/fe_operators.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace physarum {

namespace {

// The rotation that turns halfedge i of face f onto its twin j of face g: the edge runs P -> Q in f
// and Q -> P in g, so the direction P -> Q becomes g's corner j+1 -> corner j.
Rotation2 transition_across(const std::array<Eigen::Vector2d, 3>& from, int i, const std::array<Eigen::Vector2d, 3>& to,
                         int j) {
  const Eigen::Vector2d& p = from[i];
  const Eigen::Vector2d& q = from[(i + 1) % 3];
  const Eigen::Vector2d& p_image = to[(j + 1) % 3];
  const Eigen::Vector2d& q_image = to[j];
  const Eigen::Vector2d u = (q - p).normalized();
  const Eigen::Vector2d v = (q_image - p_image).normalized();
  Rotation2 r;
  r.cos_angle = u.dot(v);
  r.sin_angle = u.x() * v.y() - u.y() * v.x();
  // Renormalise so the rotation stays orthogonal to rounding error.
  const double norm = std::hypot(r.cos_angle, r.sin_angle);
  r.cos_angle /= norm;
  r.sin_angle /= norm;
  return r;
}

}  // namespace

SurfaceDomain build_surface_domain(const IntrinsicMesh& mesh, const IntrinsicFaceData<double>& face_weight) {
  const int nf = mesh.face_count();
  if (static_cast<int>(mesh.edge_lengths.size()) != nf || static_cast<int>(mesh.twin.size()) != nf)
    throw InputError("intrinsic mesh: " + std::to_string(nf) + " faces but " + std::to_string(mesh.edge_lengths.size()) +
                     " edge-length rows and " + std::to_string(mesh.twin.size()) + " twin rows");
  if (nf == 0) throw InputError("intrinsic mesh: no faces");
  if (!face_weight.empty() && static_cast<int>(face_weight.size()) != nf)
    throw InputError("face weights: " + std::to_string(face_weight.size()) + " values for " + std::to_string(nf) + " faces");

  SurfaceDomain d;
  d.vertex_count = mesh.vertex_count;
  d.face_count = nf;
  d.face_vertices = mesh.faces;
  d.face_corners.resize(nf);
  d.face_area.assign(static_cast<size_t>(nf), 0.0);
  d.face_neighbour.resize(nf);
  d.neighbour_edge.resize(nf);
  d.edge_transition.assign(3 * static_cast<size_t>(nf), Rotation2{});

  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k];
      if (v < 0 || v >= mesh.vertex_count)
        throw InputError("intrinsic mesh: face " + std::to_string(f) + " uses vertex " + std::to_string(v) + " of " +
                         std::to_string(mesh.vertex_count));
    }
    validate_face_lengths(mesh, f);
    d.face_corners[f] = layout_triangle(mesh.edge_lengths[f]);
    d.face_area[f] = triangle_area_from_lengths(mesh.edge_lengths[f]);
    d.total_area += d.face_area[f];
  }

  for (int f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const int t = mesh.twin[f][i];
      if (t < 0) {
        d.face_neighbour[f][i] = -1;
        d.neighbour_edge[f][i] = -1;
        continue;
      }
      const int g = t / 3, j = t % 3;
      if (t >= 3 * nf || mesh.twin[g][j] != 3 * f + i)
        throw InputError("intrinsic mesh: halfedge " + std::to_string(3 * f + i) + " has twin " + std::to_string(t) +
                         " whose twin is not it");
      const int a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      if (mesh.faces[g][j] != b || mesh.faces[g][(j + 1) % 3] != a)
        throw InputError("intrinsic mesh: halfedge " + std::to_string(3 * f + i) + " and its twin " + std::to_string(t) +
                         " do not join the same two vertices in opposite directions");
      const double la = mesh.edge_lengths[f][i], lb = mesh.edge_lengths[g][j];
      if (std::abs(la - lb) > 1e-9 * std::max(la, lb))
        throw InputError("intrinsic mesh: halfedge " + std::to_string(3 * f + i) + " has length " + std::to_string(la) +
                         " but its twin " + std::to_string(t) + " has length " + std::to_string(lb));
      d.face_neighbour[f][i] = g;
      d.neighbour_edge[f][i] = j;
      d.edge_transition[3 * f + i] = transition_across(d.face_corners[f], i, d.face_corners[g], j);
    }
  }

  d.vertex_mass = IntrinsicVertexData<double>(lumped_mass(mesh));
  d.vertex_location = IntrinsicVertexData<SurfacePoint>(mesh.vertex_location);
  d.laplacian = CsrMatrix::from_eigen(cotan_laplacian(mesh));

  std::vector<double> sampling_weight(d.face_area.values());
  if (!face_weight.empty())
    for (int f = 0; f < nf; ++f) {
      if (!std::isfinite(face_weight[f]) || face_weight[f] < 0.0)
        throw InputError("face weights: face " + std::to_string(f) + " has weight " + std::to_string(face_weight[f]) +
                         " (must be finite and >= 0)");
      sampling_weight[f] *= face_weight[f];
    }
  d.face_sampler = AliasTable::build(sampling_weight);
  return d;
}

Eigen::Vector3d barycentric_in_face(const SurfaceDomain& domain, int face, const Eigen::Vector2d& point) {
  // In the face frame corner 0 is the origin and corner 1 lies on the x axis, so the coordinates
  // solve a triangular system: y fixes b2, then x fixes b1.
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[face];
  const double b2 = point.y() / c[2].y();
  const double b1 = (point.x() - b2 * c[2].x()) / c[1].x();
  return {1.0 - b1 - b2, b1, b2};
}

}  // namespace physarum
