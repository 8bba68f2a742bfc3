#pragma once
// Where a sketch window lies on the surface it drives (../shared/DESIGN.md, "Sketches"), and how
// window lengths, areas and shapes become the surface's.
//
//   patch  the window [0, w] x [0, h] maps onto the input mesh's own x/y extent (a PNG as it is
//          seen: its top row at the largest y): one linear map for the whole surface;
//   uv     the window is the mesh's UV layout, [0, w] x [0, h] onto UV [0, 1]^2 (a PNG as it is seen
//          in a paint program: its top row at v = 1), so a sketch is painted on the texture the mesh
//          wears. Each face's UV triangle and its triangle on the surface give that face's own linear
//          map, the UV layout's stretch: a round mark on a stretched part of the layout is an
//          elongated spot on the surface, as the texture would show it;
//   surface marks drawn on the surface itself (common/sketch/surface_marks.hpp): no window; lengths
//          are the input mesh's, times its scale.
//
// Either way the mesh is scaled to `area` m^2 as scale_to_area does, and every map is a WindowFrame:
// window vectors to metres in a tangent frame of the surface.
#include "common/mesh/closest_point.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/sketch/sketch.hpp"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace physarum {

// The linear map from window vectors to the surface at one place: a window vector w is
// `stretch * w` metres in the orthonormal tangent basis `frame` (input coordinates), `frame *
// stretch * w` in 3D.
struct WindowFrame {
  Eigen::Matrix<double, 3, 2> frame = Eigen::Matrix<double, 3, 2>::Identity();
  Eigen::Matrix2d stretch = Eigen::Matrix2d::Identity();

  double area_factor() const;    // m^2 per window unit^2
  double length_factor() const;  // sqrt(area_factor): a length in no particular direction
  Eigen::Vector3d to_surface(const Eigen::Vector2d& window_vector) const;  // metres, 3D
};

// An ellipse's shape as its second-moment tensor, up to scale: d d^T + aspect^2 n n^T for the major
// axis d at `degrees` (counterclockwise from the basis' first axis) and n across it.
Eigen::Matrix2d shape_tensor(double aspect, double degrees);
// A shape tensor's aspect (minor / major, in [0, 1]) and major axis (degrees in [0, 180)).
struct EllipseShape {
  double aspect = 1.0;
  double orientation = 0.0;
};
EllipseShape ellipse_shape(const Eigen::Matrix2d& tensor);
// A window ellipse as the surface sees it (in the frame's basis), and a surface ellipse (in the
// frame's basis) as it would have been drawn in the window.
EllipseShape on_surface(const WindowFrame& at, const EllipseShape& window_ellipse);
EllipseShape in_window(const WindowFrame& at, const EllipseShape& surface_ellipse);

class SketchDomain {
 public:
  // InputError when the area is not > 0, or the mesh has no extent in x or y.
  static SketchDomain patch(const Sketch& sketch, const InputMesh& mesh, double area);
  // InputError when the area is not > 0, the mesh has no texture coordinates, or no UV triangle
  // has an area.
  static SketchDomain uv(const Sketch& sketch, const InputMesh& mesh, double area);
  // InputError when the area is not > 0. Every map is the scale, in an arbitrary tangent basis.
  static SketchDomain surface(const Sketch& sketch, const InputMesh& mesh, double area);

  bool on_uv() const { return on_uv_; }
  const Eigen::Vector2d& window() const { return window_; }
  double scale() const { return scale_; }  // metres per input unit

  // The map at a window point: the patch's one, or the face whose UV triangle holds the point (the
  // nearest UV triangle where none does: a gap in the layout).
  WindowFrame frame_at(const Eigen::Vector2d& window_point) const;
  // The map of an input face (the patch's one for a patch).
  WindowFrame frame_of_face(size_t face) const;
  // The window point of a point on the surface (its nearest face's UV for a UV sketch) and that
  // face's map.
  struct Located {
    Eigen::Vector2d window_point;
    WindowFrame frame;
  };
  Located locate(const Eigen::Vector3d& input_point) const;
  // The window points of an input vertex: one per distinct UV of its corners (several on a seam),
  // and the UV chart of each (vertex_charts, in the same order).
  std::vector<Eigen::Vector2d> vertex_window_points(size_t vertex) const;
  std::vector<int> vertex_charts(size_t vertex) const;
  Eigen::Vector2d face_window_point(size_t face) const;  // the centroid's
  // UV charts: the pieces of the layout whose triangles share UV edges, numbered from 0; -1 on a
  // patch (one piece) and, for a window point, in a gap between charts.
  int face_chart(size_t face) const { return on_uv_ ? face_chart_[face] : -1; }
  int chart_at(const Eigen::Vector2d& window_point) const;
  // The point of the input surface at a window point (input coordinates): on a patch its x/y with the
  // z of the nearest input vertex (a flat patch's own); nothing where a UV sketch has no face.
  std::optional<Eigen::Vector3d> surface_point(const Eigen::Vector2d& window_point) const;
  double surface_area() const { return surface_area_; }  // m^2

 private:
  SketchDomain(const Sketch& sketch, const InputMesh& mesh, double area);
  // A UV sketch: the face whose UV triangle holds w (barycentric coordinates in `bary`), else the
  // nearest one by centroid (bary clamped into it).
  size_t uv_face(const Eigen::Vector2d& w, Eigen::Vector3d& bary) const;
  Eigen::Vector2d corner_window_point(size_t face, int corner) const;

  const InputMesh* mesh_ = nullptr;
  bool on_uv_ = false;
  Eigen::Vector2d window_ = Eigen::Vector2d::Ones();
  double scale_ = 1.0, surface_area_ = 0.0;
  Eigen::Vector2d low_ = Eigen::Vector2d::Zero(), high_ = Eigen::Vector2d::Ones();  // a patch's x/y extent
  WindowFrame patch_frame_;
  std::vector<WindowFrame> face_frames_;  // a UV sketch's, per input face
  std::vector<std::vector<Eigen::Vector2d>> vertex_points_;  // a UV sketch's, per input vertex
  std::vector<std::vector<int>> vertex_point_charts_;        // ... and their charts
  std::vector<int> face_chart_;                              // a UV sketch's, per input face
  std::shared_ptr<const FaceLocator> locator_;
};

}  // namespace physarum
