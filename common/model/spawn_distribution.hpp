#pragma once
// Where (re)spawned agents appear (paper Sec. 3.3: spawn weights, sources and sinks), shared by both
// backends' model. The base model spawns uniformly by area (the domain's own face sampler); with a
// spawn-weight map or a sink the density becomes proportional to the weight interpolated LINEARLY
// across each face, sampled exactly in two bounded stages:
//
//   1. the face, with probability proportional to area x mean corner weight (the integral of the
//      linear weight over the face), through an alias table;
//   2. the point inside it: the linear density sum_i w_i b_i (b the barycentric coordinates) is the
//      mixture over corners i, with probability w_i / sum w, of the densities 3 b_i, i.e. of
//      Dirichlet(2, 1, 1) toward corner i. So: pick corner i, draw b_i ~ Beta(2, 2) by inverting its
//      CDF 3x^2 - 2x^3 in closed form (x = 1/2 + sin(asin(2u - 1) / 3)), and split 1 - b_i
//      uniformly between the other two corners (given b_i they are uniform on the segment).
//
// A face that touches a sink vertex (hazard rate +infinity, i.e. mean lifetime 0) gets weight zero,
// so no agent is ever born where it would be removed at once; a face whose three corners weigh zero
// gets none either. All weights zero is a scene error (InputError).
#include "common/base/alias_table.hpp"
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"
#include "common/base/random_streams.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Core>

namespace physarum {

struct SpawnDistribution {
  // false: the base model, the domain's face sampler and a uniform point in the face (bit for bit as
  // before controls existed). The members below are then empty.
  bool weighted = false;
  AliasTable face_sampler;                     // area x mean corner weight, 0 on faces touching a sink
  IntrinsicVertexData<double> vertex_weight;   // the linear density's corner values (>= 0)
};

// Validates spawn_weight (empty, or one finite value >= 0 per vertex; InputError naming the vertex
// otherwise) and builds the distribution. Weighted when spawn_weight is given or any hazard rate is
// +infinity (a sink); all-zero weights after the sinks are removed throw InputError.
SpawnDistribution build_spawn_distribution(const SurfaceDomain& domain, const IntrinsicVertexData<double>& spawn_weight,
                                           const IntrinsicVertexData<double>& hazard_rate);

// Beta(2, 2) from one uniform u in (0, 1), by the closed-form inverse of its CDF (header comment).
double beta22_from_uniform(double u);

// The barycentric coordinates of a point with density proportional to sum_i w_i b_i in a face with
// corner weights w (not all zero): corner from u_corner, its coordinate from u_beta, the split of
// the rest from u_split.
Eigen::Vector3d linear_density_barycentric(const Eigen::Vector3d& w, double u_corner, double u_beta, double u_split);

// A (re)spawn point. Unweighted: sample_surface_point(face_choice, in_face) exactly. Weighted: the
// face from the distribution's alias table (face_choice), the point from the linear density
// (u_corner = first uniform of corner_choice, u_beta and u_split the two uniforms of in_face).
FacePoint sample_spawn_point(const SurfaceDomain& domain, const SpawnDistribution& spawn, const PhiloxWords& face_choice,
                             const PhiloxWords& in_face, const PhiloxWords& corner_choice);

}  // namespace physarum
