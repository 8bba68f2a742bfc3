#pragma once
// One set of points on which two arms on different triangulations of the same input surface are
// measured (`physarum compare --arm max_circumradius=... --arm max_circumradius=...`): the finer
// arm's intrinsic vertices, each a point of the input surface. The finer arm's field is read there
// as it is; the coarser arm's field is read there as its discretisation defines it, linear in each of
// ITS intrinsic triangles (common/surface/intrinsic_point_location.hpp). Both are then measured by
// one operator on one set of points (common/harness/smoothing_spectrum.hpp), so a difference in a
// pattern-scale metric is a difference between the fields, not between two measurements: a coarse
// arm whose triangles cannot carry the pattern shows up as the power it lacks.
#include "common/surface/prepared_surface.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace physarum {

// The edge length of an equilateral triangle of the domain's mean face area.
double mean_edge_length(const SurfaceDomain& domain);

class CommonSampling {
 public:
  // The finer of `a` and `b` (more intrinsic vertices; `a` on a tie) is the sampling. InputError
  // when they are not triangulations of one input surface (other triangles, or other positions: a
  // different mesh or scale_to_area), saying so.
  CommonSampling(std::shared_ptr<const PreparedSurface> a, std::shared_ptr<const PreparedSurface> b);

  // The surface whose intrinsic vertices are the samples, and its domain (masses, Laplacian).
  const PreparedSurface& surface() const { return *finer_; }
  const SurfaceDomain& domain() const { return finer_->domain; }
  // The mean edge length of the samples' triangulation (common/harness/comparison_metrics.hpp).
  double edge_length() const { return edge_length_; }
  // The mean edge length of the coarser arm's triangulation.
  double coarser_edge_length() const { return coarser_edge_length_; }

  // The operator taking a field on `arm`'s intrinsic vertices to the samples (rows: samples); an
  // empty matrix when `arm` is the sampling surface itself (read as it is).
  Eigen::SparseMatrix<double, Eigen::RowMajor> from(const PreparedSurface& arm) const;
  // `field` on `arm`'s vertices read at the samples, with `to_samples` = from(arm).
  static Eigen::VectorXd read(const Eigen::SparseMatrix<double, Eigen::RowMajor>& to_samples, const Eigen::VectorXd& field);

 private:
  std::shared_ptr<const PreparedSurface> finer_;
  double edge_length_ = 0.0;
  double coarser_edge_length_ = 0.0;
};

// Whether `a` and `b` are triangulations of one input surface (same triangles, same positions), and
// if not, why (one sentence).
bool same_input_surface(const PreparedSurface& a, const PreparedSurface& b, std::string* why_not = nullptr);

}  // namespace physarum
