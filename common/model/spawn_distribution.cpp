#include "common/model/spawn_distribution.hpp"

#include "common/model/domain_sampling.hpp"
#include "common/base/errors.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace physarum {

SpawnDistribution build_spawn_distribution(const SurfaceDomain& domain, const IntrinsicVertexData<double>& spawn_weight,
                                           const IntrinsicVertexData<double>& hazard_rate) {
  const size_t n = static_cast<size_t>(domain.vertex_count);
  if (!spawn_weight.empty() && spawn_weight.size() != n)
    throw InputError("spawn weights: " + std::to_string(spawn_weight.size()) + " values for " + std::to_string(n) +
                     " vertices");
  for (size_t i = 0; i < spawn_weight.size(); ++i)
    if (!std::isfinite(spawn_weight[i]) || spawn_weight[i] < 0.0)
      throw InputError("spawn weights: vertex " + std::to_string(i) + " has weight " + std::to_string(spawn_weight[i]) +
                       " (must be finite and >= 0)");
  bool any_sink = false;
  for (double h : hazard_rate) any_sink = any_sink || std::isinf(h);

  SpawnDistribution spawn;
  if (spawn_weight.empty() && !any_sink) return spawn;  // the base model
  spawn.weighted = true;
  spawn.vertex_weight = spawn_weight.empty() ? IntrinsicVertexData<double>(n, 1.0) : spawn_weight;
  std::vector<double> face_weight(static_cast<size_t>(domain.face_count), 0.0);
  double total = 0.0;
  for (int f = 0; f < domain.face_count; ++f) {
    const std::array<int, 3>& v = domain.face_vertices[f];
    bool touches_sink = false;
    double corner_sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      touches_sink = touches_sink || (!hazard_rate.empty() && std::isinf(hazard_rate[v[k]]));
      corner_sum += spawn.vertex_weight[v[k]];
    }
    // The integral of the linear weight over the face: area x mean of the corner values.
    face_weight[static_cast<size_t>(f)] = touches_sink ? 0.0 : domain.face_area[f] * corner_sum / 3.0;
    total += face_weight[static_cast<size_t>(f)];
  }
  if (!(total > 0.0))
    throw InputError(std::string("spawn weights: every face has spawn weight zero") +
                     (any_sink ? " once the faces touching a sink (mean_lifetime 0) are excluded" : "") +
                     ": agents could be born nowhere");
  spawn.face_sampler = AliasTable::build(face_weight);
  return spawn;
}

double beta22_from_uniform(double u) { return 0.5 + std::sin(std::asin(2.0 * u - 1.0) / 3.0); }

Eigen::Vector3d linear_density_barycentric(const Eigen::Vector3d& w, double u_corner, double u_beta, double u_split) {
  // The corner, with probability w_i / sum w (a zero-weight corner is never picked: u_corner > 0).
  const double target = u_corner * (w[0] + w[1] + w[2]);
  const int corner = target < w[0] ? 0 : (target < w[0] + w[1] ? 1 : 2);
  const double toward = beta22_from_uniform(u_beta);
  Eigen::Vector3d b;
  b[corner] = toward;
  b[(corner + 1) % 3] = (1.0 - toward) * (1.0 - u_split);
  b[(corner + 2) % 3] = (1.0 - toward) * u_split;
  return b;
}

FacePoint sample_spawn_point(const SurfaceDomain& domain, const SpawnDistribution& spawn, const PhiloxWords& face_choice,
                             const PhiloxWords& in_face, const PhiloxWords& corner_choice) {
  if (!spawn.weighted) return sample_surface_point(domain, face_choice, in_face);
  FacePoint p;
  p.face = spawn.face_sampler.sample(first_uniform(face_choice), second_uniform(face_choice));
  const std::array<int, 3>& v = domain.face_vertices[p.face];
  const Eigen::Vector3d w(spawn.vertex_weight[v[0]], spawn.vertex_weight[v[1]], spawn.vertex_weight[v[2]]);
  const Eigen::Vector3d b =
      linear_density_barycentric(w, first_uniform(corner_choice), first_uniform(in_face), second_uniform(in_face));
  const std::array<Eigen::Vector2d, 3>& c = domain.face_corners[p.face];
  p.position = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
  return p;
}

}  // namespace physarum
