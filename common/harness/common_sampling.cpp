#include "common/harness/common_sampling.hpp"

#include "common/base/errors.hpp"
#include "common/surface/intrinsic_point_location.hpp"

#include <cmath>
#include <vector>

namespace physarum {

double mean_edge_length(const SurfaceDomain& domain) {
  return std::sqrt(4.0 / std::sqrt(3.0) * domain.total_area / domain.face_count);
}

bool same_input_surface(const PreparedSurface& a, const PreparedSurface& b, std::string* why_not) {
  const InputMesh &x = a.simulated, &y = b.simulated;
  std::string why;
  if (x.triangles != y.triangles) why = "the arms' input meshes have other triangles";
  else if (x.positions != y.positions) why = "the arms' input meshes have other vertex positions (another mesh or scale_to_area)";
  if (why_not) *why_not = why;
  return why.empty();
}

CommonSampling::CommonSampling(std::shared_ptr<const PreparedSurface> a, std::shared_ptr<const PreparedSurface> b) {
  std::string why;
  if (!same_input_surface(*a, *b, &why))
    throw InputError("compare: no common sampling of the two arms: " + why);
  const bool a_finer = a->domain.vertex_count >= b->domain.vertex_count;
  finer_ = a_finer ? a : b;
  edge_length_ = mean_edge_length(finer_->domain);
  coarser_edge_length_ = mean_edge_length((a_finer ? b : a)->domain);
}

Eigen::SparseMatrix<double, Eigen::RowMajor> CommonSampling::from(const PreparedSurface& arm) const {
  if (&arm == finer_.get()) return {};
  std::vector<SurfacePoint> samples(finer_->domain.vertex_location.begin(), finer_->domain.vertex_location.end());
  return interpolation_at_points(arm.simulated, arm.domain, samples);
}

Eigen::VectorXd CommonSampling::read(const Eigen::SparseMatrix<double, Eigen::RowMajor>& to_samples, const Eigen::VectorXd& field) {
  if (to_samples.rows() == 0) return field;
  return to_samples * field;
}

}  // namespace physarum
