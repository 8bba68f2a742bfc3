// Outflow extrapolation at the boundary (common/map_tools/boundary_outflow.hpp), on a jittered flat square
// (every face has a frame of its own, so directions really are carried across edges) with a radial
// field from a point just outside the corner at the origin: it leaves the square through the two far
// sides (x = 1, y = 1) and enters through the two near ones. The boundary faces get a wrong field
// (turned by 60 degrees); the faces at the far sides must come back to the radial direction, those
// at the near sides must be left as they are.
#include "common/map_tools/boundary_outflow.hpp"
#include "map_tool_meshes.hpp"
#include "pheromone_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace physarum {
namespace {

struct RadialSquare {
  InputMesh mesh = testing::make_flat_rectangle(0.0, 1.0, 0.0, 1.0, 16, 16, 0.2);
  SurfaceDomain domain = testing::make_domain(mesh);
  Eigen::Vector2d source{-0.1, -0.1};
  std::vector<char> on_boundary;

  RadialSquare() {
    for (const Eigen::Vector3d& p : mesh.positions)
      on_boundary.push_back(p.x() == 0.0 || p.x() == 1.0 || p.y() == 0.0 || p.y() == 1.0);
  }
  bool touches(int face, auto predicate) const {
    for (const int v : domain.face_vertices[static_cast<size_t>(face)])
      if (predicate(mesh.positions[static_cast<size_t>(v)])) return true;
    return false;
  }
  bool on_far_side(int face) const {
    return touches(face, [](const Eigen::Vector3d& p) { return p.x() == 1.0 || p.y() == 1.0; });
  }
  // The plane's direction d carried into the face's own frame (the layout is the face turned and
  // moved in the plane: the linear map taking its 3D edges to its layout's edges).
  Eigen::Vector2d in_frame(int face, const Eigen::Vector2d& d) const {
    const auto& v = domain.face_vertices[static_cast<size_t>(face)];
    const auto& c = domain.face_corners[static_cast<size_t>(face)];
    Eigen::Matrix2d layout, plane;
    layout << c[1] - c[0], c[2] - c[0];
    plane << (mesh.positions[v[1]] - mesh.positions[v[0]]).head<2>(), (mesh.positions[v[2]] - mesh.positions[v[0]]).head<2>();
    return layout * plane.inverse() * d;
  }
  Eigen::Vector2d radial(int face) const {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const int v : domain.face_vertices[static_cast<size_t>(face)]) centroid += mesh.positions[v].head<2>() / 3.0;
    return in_frame(face, (centroid - source).normalized());
  }
  // The radial field, turned by 60 degrees in the faces that touch the boundary.
  FaceDirection corrupted() const {
    return [this](int face) -> std::optional<Eigen::Vector2d> {
      const Eigen::Vector2d r = radial(face);
      if (!touches(face, [](const Eigen::Vector3d& p) { return p.x() == 0.0 || p.x() == 1.0 || p.y() == 0.0 || p.y() == 1.0; }))
        return r;
      return Eigen::Rotation2Dd(std::numbers::pi / 3.0) * r;
    };
  }
};

TEST(BoundaryOutflow, FacesWhereTheFieldLeavesTakeTheInteriorDirectionTheOthersKeepTheirs) {
  const RadialSquare s;
  const std::vector<FaceDirectionOverride> out =
      outflow_directions(s.domain, s.on_boundary, std::vector<char>(s.on_boundary.size(), 0), s.corrupted());
  std::vector<int> replaced(static_cast<size_t>(s.domain.face_count), -1);
  for (size_t i = 0; i < out.size(); ++i) {
    if (i > 0) {
      EXPECT_LT(out[i - 1].face, out[i].face) << "not in increasing face order";
    }
    replaced[static_cast<size_t>(out[i].face)] = static_cast<int>(i);
  }
  int far = 0;
  for (int face = 0; face < s.domain.face_count; ++face) {
    const bool boundary = s.touches(face, [](const Eigen::Vector3d& p) {
      return p.x() == 0.0 || p.x() == 1.0 || p.y() == 0.0 || p.y() == 1.0;
    });
    const int r = replaced[static_cast<size_t>(face)];
    if (!boundary || !s.on_far_side(face)) {
      EXPECT_LT(r, 0) << "face " << face << (boundary ? " at a near side (inflow)" : " inside") << " was replaced";
      continue;
    }
    ++far;
    ASSERT_GE(r, 0) << "face " << face << " at a far side (outflow) was not replaced";
    const Eigen::Vector2d& d = out[static_cast<size_t>(r)].direction;
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    // The interior faces one or two rings in point along the radius through them: within the angle
    // that radius turns over a ring (h / r: 1/16 over r >= 1.1) of this face's own.
    EXPECT_LT(std::acos(std::min(1.0, d.dot(s.radial(face)))), 0.1) << "face " << face;
  }
  EXPECT_GT(far, 60);  // both far sides: 2 x 16 cells, two or three faces each
}

TEST(BoundaryOutflow, FacesTouchingAKeptVertexAreLeftAlone) {
  const RadialSquare s;
  std::vector<char> keep(s.on_boundary.size(), 0);
  for (size_t v = 0; v < keep.size(); ++v) keep[v] = s.mesh.positions[v].x() == 1.0;
  for (const FaceDirectionOverride& o : outflow_directions(s.domain, s.on_boundary, keep, s.corrupted()))
    EXPECT_FALSE(s.touches(o.face, [](const Eigen::Vector3d& p) { return p.x() == 1.0; })) << "face " << o.face;
}

}  // namespace
}  // namespace physarum
