#pragma once
// A signpost intrinsic triangulation (Sharp, Soliman & Crane 2019, "Navigating intrinsic
// triangulations") of an input surface: the same surface, re-triangulated with edges that are
// geodesics ON it. Edge flips make it intrinsically Delaunay (non-negative cotan weights, the
// property the FE operators need); circumcenter insertion refines it to a maximum circumradius and
// optionally a minimum angle. Each vertex knows where it sits on the input mesh, so results can be
// carried back onto the input.
//
// Storage: flat arrays indexed by halfedge h = 3f + i, running from corner i of face f to corner
// (i+1)%3, exactly the layout of IntrinsicMesh. Signposts: the direction of each halfedge at its
// tail, as an angle in the tail vertex's "normalized" tangent coordinates, where angles are
// measured counter-clockwise from a reference halfedge and rescaled by 2 pi / (angle sum) at
// interior vertices and by pi / (angle sum) at boundary vertices (whose reference is the outgoing
// boundary halfedge, so their directions span [0, pi]).
#include "common/mesh/input_mesh.hpp"
#include "common/intrinsic/intrinsic_mesh.hpp"
#include "common/mesh/surface_point.hpp"

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace physarum {

struct RefinementOptions {
  // Every face's circumradius must end up at most this (absolute units of the input).
  double max_circumradius = std::numeric_limits<double>::infinity();
  // Every corner angle must end up at least this many degrees; 0 turns the criterion off. Values
  // above ~30 degrees may not terminate (Chew's second algorithm), so they are rejected above 35.
  double min_angle_deg = 0.0;
  // Budget of vertex insertions (circumcenters plus boundary midpoints). Exceeding it is an
  // InputError: a request that would need more vertices than this is almost surely a mistake.
  size_t max_insertions = 10'000'000;
};

// Why refinement left a face that violates the requested bounds.
enum class RefinementGuard {
  // Exactly one corner of the face sits at a vertex with angle sum < 60 degrees (a sharp cone or
  // boundary corner). Refining there never ends: every inserted circumcenter makes new skinny faces
  // at the cone. geometry-central skips the same faces (the same "exactly one" rule).
  NeedleVertex,
  // The small angle lies between two boundary edges, or at a vertex of degree one: no insertion
  // can make that corner larger.
  UnimprovableCorner,
  // The circumcenter would land within a tiny distance (1e-6 of the circumradius) of an existing
  // vertex: inserting it would create a near-zero edge (only happens through rounding).
  InsertionTooClose,
  // The straight walk to the circumcenter did not finish within kMaxTraceSteps faces.
  TraceFailed,
  // Still violating after the final re-scans (should not happen; reported rather than hidden).
  Unresolved,
};

std::string to_string(RefinementGuard guard);

struct SkippedFace {
  int face = -1;  // face index in the final triangulation (snapshot())
  RefinementGuard guard = RefinementGuard::NeedleVertex;
  double circumradius = 0.0;
  double min_angle_deg = 0.0;
};

struct RefinementResult {
  size_t circumcenter_insertions = 0;
  size_t boundary_splits = 0;  // boundary edges split at their midpoint (circumcenter outside)
  size_t flips = 0;            // flips done by this call
  // Faces of the final triangulation that still violate a requested bound, each with the guard
  // that kept it. Everything else satisfies the bounds.
  std::vector<SkippedFace> skipped_faces;

  size_t insertions() const { return circumcenter_insertions + boundary_splits; }
};

class IntrinsicTriangulation {
 public:
  // Throws InputError (naming mesh.source and the first offending element) for a mesh that is not
  // manifold/oriented, has a zero-length edge or a vertex with more than one fan.
  explicit IntrinsicTriangulation(const InputMesh& mesh);

  // Flips every non-Delaunay interior edge (cotan weight < 0) until none is left; returns the
  // number of flips made by this call.
  size_t flip_to_delaunay();

  // Delaunay refinement (Chew's second algorithm on the intrinsic surface); flips to Delaunay first.
  RefinementResult refine(const RefinementOptions& options);

  IntrinsicMesh snapshot() const;

  int vertex_count() const { return static_cast<int>(vertex_angle_sum_.size()); }
  int face_count() const { return static_cast<int>(tail_.size() / 3); }
  int input_vertex_count() const { return input_vertex_count_; }

  // True when every interior edge has cotan weight (cot a + cot b)/2 >= -rel_tol * max(1, largest |weight|).
  bool is_delaunay(double rel_tol = 1e-9) const;
  double min_angle_deg() const;
  double max_circumradius() const;
  double total_area() const;
  size_t flip_count() const { return flip_count_; }
  size_t insertion_count() const { return insertion_count_; }

  // Per-element accessors (for tests and diagnostics).
  double edge_length(int halfedge) const { return length_[halfedge]; }
  double signpost_angle(int halfedge) const { return signpost_[halfedge]; }
  double vertex_angle_sum(int vertex) const { return vertex_angle_sum_[vertex]; }
  bool is_boundary_vertex(int vertex) const { return vertex_is_boundary_[vertex]; }
  const SurfacePoint& vertex_location(int vertex) const { return vertex_location_[vertex]; }
  double face_circumradius(int face) const;
  double face_min_angle_deg(int face) const;
  double face_area(int face) const;
  double cotan_weight(int halfedge) const;  // (cot a + cot b)/2 of the edge; one side only on a boundary

  // Empty when the halfedge structure, lengths, signposts and angle sums agree with each other;
  // otherwise a description of the first inconsistency (for tests and debugging).
  std::string check_consistency() const;

 private:
  struct WalkResult;
  struct Halfedges {
    std::vector<int> twin;
    std::vector<double> length;
  };

  class Refinement;  // one refine() call's queues and bookkeeping (intrinsic_refinement.cpp)

  // ---- construction: the constructor's steps, in order ----
  void read_input_corners(const InputMesh& mesh);
  void match_input_twins();
  std::vector<int> find_input_fans(int nv);  // returns each vertex's corner count
  void measure_input_angles(const std::vector<int>& corner_count);
  void start_from_input();

  // ---- elementary navigation ----
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  int head(int h) const { return tail_[next(h)]; }
  double corner_angle_at(int h) const;  // interior angle of face h/3 at the tail of h
  double vertex_scale(int v) const;     // normalized angle per radian at v

  // ---- mutations ----
  // Writes halfedge slot h: its tail vertex, intrinsic length, signpost at the tail and twin.
  void set_halfedge(int h, int tail, double length, double signpost, int twin) {
    tail_[h] = tail;
    length_[h] = length;
    signpost_[h] = signpost;
    twin_[h] = twin;
  }
  // Resizes the per-halfedge arrays to the slots of `faces` faces; new slots start off the edge queue.
  void resize_halfedge_slots(int faces);
  bool edge_is_delaunay(int h, double tolerance) const;
  // Edges whose cotan weight is above -kDelaunayTolerance count as Delaunay when flipping and
  // refining (cotangents are dimensionless, so an absolute tolerance is scale-free). Flipping a
  // co-circular edge back and forth is what the tolerance prevents.
  static constexpr double kDelaunayTolerance = 1e-10;
  bool flip_edge(int h);  // false when the flip would be invalid/degenerate
  void remap_after_rewrite(const int* old_halfedges, const int* new_halfedges, int surviving, int count);
  int insert_in_face(int face, const std::array<Eigen::Vector2d, 3>& corners, const Eigen::Vector2d& point,
                     const Eigen::Vector2d& arrival_direction, int source_vertex, double source_angle,
                     double distance);
  int split_boundary_edge(int h);
  int encroached_boundary_edge(int face, const std::array<Eigen::Vector2d, 3>& corners,
                               const Eigen::Vector2d& point) const;

  // ---- locating new vertices on the input mesh ----
  void trace_on_input(int source_vertex, double normalized_angle, double distance, SurfacePoint& location,
                      double& arrival_angle_in_face) const;

  // ---- flipping with a work queue ----
  void enqueue_edge(int h);
  size_t flip_queued_edges(std::vector<int>* touched_faces);

  std::string source_;
  int input_vertex_count_ = 0;

  // Input mesh (never changes): halfedge structure, lengths and signposts of the input triangles.
  Halfedges input_;
  std::vector<double> input_signpost_;
  std::vector<int> input_first_outgoing_;  // per input vertex; the boundary halfedge at boundary vertices

  // Intrinsic triangulation.
  std::vector<int> tail_;
  std::vector<int> twin_;
  std::vector<double> length_;
  std::vector<double> signpost_;
  std::vector<int> outgoing_;  // per vertex; the outgoing boundary halfedge at boundary vertices
  std::vector<double> vertex_angle_sum_;
  std::vector<char> vertex_is_boundary_;
  std::vector<SurfacePoint> vertex_location_;
  // For inserted vertices: normalized angle phi at the vertex points along the direction of angle
  // (phi + offset) in the canonical 2D layout of its location face (corner 0 at the origin, corner
  // 1 on the +x axis). Unused for input vertices, whose angles are the input signposts.
  std::vector<double> input_direction_offset_;
  // For inserted boundary vertices: the input boundary halfedge they lie on and the parameter.
  std::vector<int> boundary_input_halfedge_;
  std::vector<double> boundary_parameter_;

  std::vector<int> edge_queue_;
  std::vector<char> in_edge_queue_;  // per halfedge slot

  size_t flip_count_ = 0;
  size_t insertion_count_ = 0;
};

}  // namespace physarum
