#include "common/sketch/mark_moments.hpp"

#include "common/sketch/sketch.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace physarum {

void MarkMoments::add_cell(const Eigen::Vector2d& center, double side) {
  const double a = side * side;
  area_ += a;
  first_ += a * center;
  second_ += a * (center * center.transpose() + Eigen::Matrix2d::Identity() * (side * side / 12.0));
}

void MarkMoments::add(const MarkMoments& other) {
  area_ += other.area_;
  first_ += other.first_;
  second_ += other.second_;
}

Eigen::Vector2d MarkMoments::centroid() const { return first_ / area_; }

MarkMoments::Ellipse MarkMoments::ellipse() const {
  const Eigen::Vector2d c = centroid();
  const Eigen::Matrix2d covariance = second_ / area_ - c * c.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);  // ascending eigenvalues
  const Eigen::Vector2d axis = eigen.eigenvectors().col(1);
  Ellipse e;
  e.center = c;
  e.major = 2.0 * std::sqrt(std::max(0.0, eigen.eigenvalues()[1]));
  e.minor = 2.0 * std::sqrt(std::max(0.0, eigen.eigenvalues()[0]));
  e.orientation = axis_orientation(std::atan2(axis.y(), axis.x()) * 180.0 / M_PI);
  return e;
}

}  // namespace physarum
