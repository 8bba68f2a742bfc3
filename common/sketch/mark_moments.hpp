#pragma once
// The ellipse of a drawn mark from its area moments: a filled ellipse with semi-axes a >= b has the
// covariance of its area a^2/4 along its major axis and b^2/4 across, so the covariance's eigenpairs
// give the axes back exactly (up to the pixel grid). Pixels are added as little squares, each with
// its own s^2/12 of variance, so a mark a few pixels wide is not measured too thin.
#include <Eigen/Core>

namespace physarum {

class MarkMoments {
 public:
  // A square cell of side `side` centred at `center`.
  void add_cell(const Eigen::Vector2d& center, double side);
  void add(const MarkMoments& other);

  double area() const { return area_; }
  Eigen::Vector2d centroid() const;
  // Semi-axes (major >= minor >= 0) and the major axis' direction in degrees in [0, 180), of the
  // ellipse with the same area covariance. area() > 0 required.
  struct Ellipse {
    Eigen::Vector2d center;
    double major, minor, orientation;
  };
  Ellipse ellipse() const;

 private:
  double area_ = 0.0;
  Eigen::Vector2d first_ = Eigen::Vector2d::Zero();   // integral of p
  Eigen::Matrix2d second_ = Eigen::Matrix2d::Zero();  // integral of p p^T
};

}  // namespace physarum
