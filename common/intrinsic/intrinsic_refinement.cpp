// Intrinsic refinement (IntrinsicTriangulation::refine): insertion of circumcenters (tracing
// them on the input), boundary-edge splits, and the refinement loop; the mesh itself and its flips
// are in intrinsic_triangulation.cpp.
#include "common/intrinsic/intrinsic_triangulation.hpp"

#include "common/base/errors.hpp"
#include "common/intrinsic/intrinsic_geometry.hpp"
#include "common/base/number_format.hpp"
#include "common/intrinsic/unfolded_walk.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <tuple>
#include <utility>

namespace physarum {

namespace {

using namespace unfolding;
constexpr double kPi = std::numbers::pi;

// Guard against creating near-zero edges: a circumcenter this close (relative to the circumradius)
// to an existing vertex is not inserted.
constexpr double kTooCloseFraction = 1e-6;

// Inserted points are kept this far (in barycentric terms) inside their face: a sliver thinner than
// this has an area that rounding of its edge lengths cannot pin down (relative error ~ 1e-16 / this),
// and the displacement is far below any length the simulation resolves.
constexpr double kMinBarycentric = 1e-6;

// A circumcenter whose barycentric coordinate across a boundary edge is below this lies on that
// edge as far as rounding can tell.
constexpr double kOnEdgeBarycentric = 1e-9;

// How often the refinement re-scans the whole triangulation when its queues run dry, to catch
// faces missed through rounding (geometry-central does the same) without looping forever.
constexpr int kMaxRechecks = 5;


}  // namespace


// Vertex insertion
// ------------------------------------------------------------------------------------------------

void IntrinsicTriangulation::trace_on_input(int source_vertex, double normalized_angle, double distance,
                                            SurfacePoint& location, double& arrival_angle_in_face) const {
  int face = -1;
  Corners corners;
  Vector2d start, direction;
  if (source_vertex < input_vertex_count_) {
    // An input vertex: its normalized angles are those of the input fan. Find the wedge (input
    // corner) containing the direction, then turn by the remaining raw angle inside it.
    const int first = input_first_outgoing_[source_vertex];
    int h = first;
    for (int guard = 0; guard < 1 << 20; ++guard) {
      const int n = input_.twin[prev(h)];
      if (n < 0 || n == first || input_signpost_[n] > normalized_angle) break;
      h = n;
    }
    const double corner =
        geometry::corner_angle(input_.length[h], input_.length[prev(h)], input_.length[next(h)]);
    const double raw = std::clamp((normalized_angle - input_signpost_[h]) / vertex_scale(source_vertex), 0.0, corner);
    face = h / 3;
    corners = layout_face(input_.length, face, h % 3);
    start = Vector2d::Zero();
    direction = Vector2d(std::cos(raw), std::sin(raw));
  } else {
    const SurfacePoint& p = vertex_location_[source_vertex];
    face = p.face;
    corners = layout_face(input_.length, face, 0);
    start = p.barycentric[0] * corners[0] + p.barycentric[1] * corners[1] + p.barycentric[2] * corners[2];
    const double angle = normalized_angle + input_direction_offset_[source_vertex];
    direction = Vector2d(std::cos(angle), std::sin(angle));
  }
  const Walk walk = walk_straight(input_.twin, input_.length, face, corners, start, direction, distance);
  location.face = walk.face;
  location.barycentric = clamped_barycentric(
      geometry::barycentric(walk.corners[0], walk.corners[1], walk.corners[2], walk.point));
  arrival_angle_in_face = direction_angle(walk.direction) - direction_angle(walk.corners[1] - walk.corners[0]);
}

void IntrinsicTriangulation::resize_halfedge_slots(int faces) {
  const size_t new_size = 3 * static_cast<size_t>(faces);
  tail_.resize(new_size);
  twin_.resize(new_size);
  length_.resize(new_size);
  signpost_.resize(new_size);
  in_edge_queue_.resize(new_size, 0);
}

int IntrinsicTriangulation::insert_in_face(int g, const Corners& corners, const Eigen::Vector2d& point,
                                           const Eigen::Vector2d& arrival_direction, int source_vertex,
                                           double source_angle, double distance) {
  const Vector3d bary = clamped_barycentric(geometry::barycentric(corners[0], corners[1], corners[2], point));
  Vector3d inside = bary;
  for (int i = 0; i < 3; ++i) inside[i] = std::max(inside[i], kMinBarycentric);
  inside /= inside.sum();
  const Vector2d p = inside[0] * corners[0] + inside[1] * corners[1] + inside[2] * corners[2];

  const int m = vertex_count();
  const int n1 = face_count(), n2 = n1 + 1;
  resize_halfedge_slots(n2 + 1);

  int u[3];
  int tw[3];
  double len[3], sp[3], r[3], alpha[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = tail_[3 * g + k];
    len[k] = length_[3 * g + k];
    sp[k] = signpost_[3 * g + k];
    tw[k] = twin_[3 * g + k];
    r[k] = (corners[k] - p).norm();
    alpha[k] = direction_angle(corners[k] - p);
  }
  double sp_to_m[3], sp_from_m[3];
  for (int k = 0; k < 3; ++k) {
    sp_to_m[k] = geometry::wrap_angle(sp[k] + vertex_scale(u[k]) * geometry::corner_angle(len[k], r[k], r[(k + 1) % 3]));
    sp_from_m[k] = geometry::wrap_angle(alpha[k] - alpha[0]);
  }
  const int face_of[3] = {g, n1, n2};
  // Face k = (u_k, u_{k+1}, m) keeps the old edge k in slot 0.
  for (int k = 0; k < 3; ++k) {
    const int f = face_of[k], fn = face_of[(k + 1) % 3], fp = face_of[(k + 2) % 3];
    const int k1 = (k + 1) % 3;
    set_halfedge(3 * f + 0, u[k], len[k], sp[k], tw[k]);
    set_halfedge(3 * f + 1, u[k1], r[k1], sp_to_m[k1], 3 * fn + 2);
    set_halfedge(3 * f + 2, m, r[k], sp_from_m[k], 3 * fp + 1);
  }
  const int old_slots[3] = {3 * g + 0, 3 * g + 1, 3 * g + 2};
  const int new_slots[3] = {3 * g + 0, 3 * n1 + 0, 3 * n2 + 0};
  remap_after_rewrite(old_slots, new_slots, 3, 3);

  vertex_angle_sum_.push_back(2.0 * kPi);
  vertex_is_boundary_.push_back(0);
  outgoing_.push_back(3 * g + 2);
  boundary_input_halfedge_.push_back(-1);
  boundary_parameter_.push_back(0.0);

  // Where the new vertex sits on the input: the same geodesic, traced on the input mesh.
  SurfacePoint location;
  double arrival_angle = 0.0;
  trace_on_input(source_vertex, source_angle, distance, location, arrival_angle);
  vertex_location_.push_back(location);
  // Tie the new vertex's angle coordinates to its input face: the direction back towards the
  // source has intrinsic angle theta_back and input angle arrival_angle + pi.
  const double theta_back = geometry::wrap_angle(direction_angle(-arrival_direction) - alpha[0]);
  input_direction_offset_.push_back(arrival_angle + kPi - theta_back);
  ++insertion_count_;
  return m;
}

int IntrinsicTriangulation::split_boundary_edge(int h) {
  const int f = h / 3;
  const int h_bc = next(h), h_ca = prev(h);
  const int a = tail_[h], b = tail_[h_bc], c = tail_[h_ca];
  const double l = length_[h], l_bc = length_[h_bc], l_ca = length_[h_ca];
  const Vector2d pa(0.0, 0.0), pb(l, 0.0);
  const Vector2d pc = geometry::layout_third_corner(pa, pb, l, l_ca, l_bc);
  const Vector2d pm(0.5 * l, 0.0);
  const double r = (pc - pm).norm();

  const int m = vertex_count();
  const int n = face_count();
  resize_halfedge_slots(n + 1);

  const double sp_ab = signpost_[h], sp_bc = signpost_[h_bc], sp_ca = signpost_[h_ca];
  const int twin_bc = twin_[h_bc], twin_ca = twin_[h_ca];
  // m is a boundary vertex with angle sum pi, so its normalized angles are raw radians from m->b.
  const double sp_mc = geometry::corner_angle(0.5 * l, r, l_bc);
  vertex_angle_sum_.push_back(kPi);
  vertex_is_boundary_.push_back(1);
  outgoing_.push_back(3 * n + 0);
  const double sp_cm = geometry::wrap_angle(sp_ca + vertex_scale(c) * geometry::corner_angle(l_ca, r, 0.5 * l));

  // f = (a, m, c), n = (m, b, c)
  set_halfedge(3 * f + 0, a, 0.5 * l, sp_ab, -1);
  set_halfedge(3 * f + 1, m, r, sp_mc, 3 * n + 2);
  set_halfedge(3 * f + 2, c, l_ca, sp_ca, twin_ca);
  set_halfedge(3 * n + 0, m, 0.5 * l, 0.0, -1);
  set_halfedge(3 * n + 1, b, l_bc, sp_bc, twin_bc);
  set_halfedge(3 * n + 2, c, r, sp_cm, 3 * f + 1);
  const int old_slots[3] = {h, h_bc, h_ca};
  const int new_slots[3] = {3 * f + 0, 3 * n + 1, 3 * f + 2};
  remap_after_rewrite(old_slots, new_slots, 3, 3);

  // Location: the intrinsic boundary edge a->b is a piece of one input boundary halfedge (boundary
  // edges are only ever split, never flipped), between parameters t_a and t_b.
  int input_h = -1;
  double t_a = 0.0, t_b = 1.0;
  if (a >= input_vertex_count_) {
    input_h = boundary_input_halfedge_[a];
    t_a = boundary_parameter_[a];
  }
  if (b >= input_vertex_count_) {
    input_h = boundary_input_halfedge_[b];
    t_b = boundary_parameter_[b];
  }
  if (input_h < 0) input_h = input_first_outgoing_[a];  // both ends are input vertices: the whole input edge
  const double t = 0.5 * (t_a + t_b);
  const int input_face = input_h / 3, k = input_h % 3;
  SurfacePoint location;
  location.face = input_face;
  location.barycentric = Vector3d::Zero();
  location.barycentric[k] = 1.0 - t;
  location.barycentric[(k + 1) % 3] = t;
  vertex_location_.push_back(location);
  boundary_input_halfedge_.push_back(input_h);
  boundary_parameter_.push_back(t);
  // Angle 0 at m points along the boundary towards b, i.e. along input halfedge input_h.
  const Corners canonical = layout_face(input_.length, input_face, 0);
  input_direction_offset_.push_back(direction_angle(canonical[(k + 1) % 3] - canonical[k]));
  ++insertion_count_;
  return m;
}

// Ruppert's rule: a new point inside the diametral disk of a boundary edge must not be inserted;
// that edge is split instead. Without it, circumcenters creep ever closer to the boundary and the
// boundary splits that follow cascade without end. Checked for the boundary edges of the face
// containing the point and of its three neighbours (the disks that can contain it in practice).
int IntrinsicTriangulation::encroached_boundary_edge(int face, const Corners& corners, const Vector2d& point) const {
  const auto encroaches = [&](const Vector2d& a, const Vector2d& b) {
    return (point - 0.5 * (a + b)).squaredNorm() < 0.25 * (b - a).squaredNorm();
  };
  for (int j = 0; j < 3; ++j) {
    const int h = 3 * face + j;
    const Vector2d& a = corners[j];
    const Vector2d& b = corners[(j + 1) % 3];
    const int t = twin_[h];
    if (t < 0) {
      if (encroaches(a, b)) return h;
      continue;
    }
    // Neighbour across edge j, unfolded: its corner k is b, k+1 is a.
    const int g = t / 3, k = t % 3;
    const int h1 = 3 * g + (k + 1) % 3, h2 = 3 * g + (k + 2) % 3;
    if (twin_[h1] >= 0 && twin_[h2] >= 0) continue;
    const Vector2d c = geometry::layout_third_corner(b, a, length_[t], length_[h2], length_[h1]);
    if (twin_[h1] < 0 && encroaches(a, c)) return h1;
    if (twin_[h2] < 0 && encroaches(c, b)) return h2;
  }
  return -1;
}

// ------------------------------------------------------------------------------------------------
// Refinement
// ------------------------------------------------------------------------------------------------

// One refine() call: the queue of faces to refine, the faces where an insertion failed, and the
// counts it reports.
class IntrinsicTriangulation::Refinement {
 public:
  Refinement(IntrinsicTriangulation& t, const RefinementOptions& options)
      : t_(t),
        options_(options),
        flips_before_(t.flip_count_),
        angle_threshold_(options.min_angle_deg * kPi / 180.0),
        max_r_(options.max_circumradius),
        failed_(t.face_count(), {RefinementGuard::TraceFailed, -1.0}) {}

  RefinementResult run();

 private:
  enum class Verdict { Fine, Refine, SkipNeedle, SkipCorner };
  using Entry = std::tuple<double, double, int>;  // (priority, area when queued, face)

  Verdict verdict(int f) const;
  double priority(int f) const;
  void consider(int f);
  const RefinementGuard* failure_of(int f) const;
  void flip_and_queue_everything();
  void refine_until_done();
  bool requeue_missed_violations();
  void check_insertion_budget() const;
  void refine_face(int f);
  void grow_failed_to_face_count();
  void requeue_around(int m);
  int insert_circumcenter(int f, RefinementGuard& refused);
  int boundary_edge_in_the_way(const Walk& walk) const;
  int insert_inside_walk_face(int f, int best, double best_angle, const Walk& walk);
  void report_skipped_faces();

  IntrinsicTriangulation& t_;
  const RefinementOptions& options_;
  RefinementResult result_;
  const size_t flips_before_;
  const double angle_threshold_;
  const double max_r_;
  std::priority_queue<Entry> face_queue_;
  // Faces where an insertion attempt failed, with their area at that time (stale once it changed).
  std::vector<std::pair<RefinementGuard, double>> failed_;
};

RefinementResult IntrinsicTriangulation::refine(const RefinementOptions& options) {
  if (!(options.max_circumradius > 0.0))
    throw InputError(source_ + ": refinement needs a positive max circumradius, got " +
                     std::to_string(options.max_circumradius));
  if (!(options.min_angle_deg >= 0.0 && options.min_angle_deg <= 35.0))
    throw InputError(source_ + ": refinement min angle must be in [0, 35] degrees (larger bounds do not terminate), got " +
                     std::to_string(options.min_angle_deg));
  return Refinement(*this, options).run();
}

RefinementResult IntrinsicTriangulation::Refinement::run() {
  flip_and_queue_everything();
  refine_until_done();
  report_skipped_faces();
  result_.flips = t_.flip_count_ - flips_before_;
  return std::move(result_);
}

IntrinsicTriangulation::Refinement::Verdict IntrinsicTriangulation::Refinement::verdict(int f) const {
  int needles = 0;
  bool small_angle = false, unimprovable = false;
  for (int i = 0; i < 3; ++i) {
    const int h = 3 * f + i;
    if (t_.vertex_angle_sum_[t_.tail_[h]] < kPi / 3.0) ++needles;
    if (angle_threshold_ > 0.0 && t_.corner_angle_at(h) < angle_threshold_) {
      const bool degree_one = prev(h) == t_.twin_[h];
      const bool between_boundaries = t_.twin_[h] < 0 && t_.twin_[prev(h)] < 0;
      if (degree_one || between_boundaries)
        unimprovable = true;
      else
        small_angle = true;
    }
  }
  const bool too_big = t_.face_circumradius(f) > max_r_;
  if (!too_big && !small_angle) return unimprovable ? Verdict::SkipCorner : Verdict::Fine;
  // Guard: exactly one corner at a needle (cone) vertex -- see RefinementGuard::NeedleVertex.
  if (needles == 1) return Verdict::SkipNeedle;
  return Verdict::Refine;
}

// Faces on the boundary first (their circumcenters may need boundary splits, which are best done
// before the interior fills up), then the largest faces: geometry-central's order.
double IntrinsicTriangulation::Refinement::priority(int f) const {
  for (int i = 0; i < 3; ++i)
    if (t_.twin_[3 * f + i] < 0) return std::numeric_limits<double>::infinity();
  return t_.face_area(f);
}

void IntrinsicTriangulation::Refinement::consider(int f) {
  if (verdict(f) == Verdict::Refine) face_queue_.emplace(priority(f), t_.face_area(f), f);
}

const RefinementGuard* IntrinsicTriangulation::Refinement::failure_of(int f) const {
  if (f < static_cast<int>(failed_.size()) && failed_[f].second >= 0.0 && failed_[f].second == t_.face_area(f))
    return &failed_[f].first;
  return nullptr;
}

void IntrinsicTriangulation::Refinement::flip_and_queue_everything() {
  for (size_t h = 0; h < t_.tail_.size(); ++h)
    if (t_.twin_[h] > static_cast<int>(h)) t_.enqueue_edge(static_cast<int>(h));
  t_.flip_queued_edges(nullptr);
  for (int f = 0; f < t_.face_count(); ++f) consider(f);
}

void IntrinsicTriangulation::Refinement::refine_until_done() {
  std::vector<int> touched;
  int rechecks = 0;
  for (;;) {
    touched.clear();
    t_.flip_queued_edges(&touched);
    for (const int f : touched) consider(f);

    if (face_queue_.empty()) {
      // Re-scan everything a few times: rounding can hide a violation from the incremental queues.
      if (rechecks++ >= kMaxRechecks) break;
      if (!requeue_missed_violations()) break;
      continue;
    }

    const auto [weight, area, f] = face_queue_.top();
    face_queue_.pop();
    (void)weight;
    // Stale entry: the face changed since it was queued (it was re-queued then if still bad).
    if (area != t_.face_area(f) || verdict(f) != Verdict::Refine || failure_of(f)) continue;

    check_insertion_budget();
    refine_face(f);
  }
}

// Queues every face that still needs refining and every non-Delaunay edge; false when there is none.
bool IntrinsicTriangulation::Refinement::requeue_missed_violations() {
  bool found = false;
  for (int f = 0; f < t_.face_count(); ++f)
    if (verdict(f) == Verdict::Refine && !failure_of(f)) {
      consider(f);
      found = true;
    }
  for (size_t h = 0; h < t_.tail_.size(); ++h)
    if (t_.twin_[h] > static_cast<int>(h) && !t_.edge_is_delaunay(static_cast<int>(h), kDelaunayTolerance)) {
      t_.enqueue_edge(static_cast<int>(h));
      found = true;
    }
  return found;
}

void IntrinsicTriangulation::Refinement::check_insertion_budget() const {
  if (result_.insertions() >= options_.max_insertions)
    throw InputError(t_.source_ + ": intrinsic refinement to max circumradius " + format_number(max_r_) +
                     (angle_threshold_ > 0.0 ? " and min angle " + format_number(options_.min_angle_deg) + " degrees"
                                             : std::string()) +
                     " needs more than the budget of " + std::to_string(options_.max_insertions) +
                     " vertex insertions (" + std::to_string(t_.vertex_count()) +
                     " vertices so far); use a larger circumradius or a smaller min angle");
}

void IntrinsicTriangulation::Refinement::refine_face(int f) {
  RefinementGuard refused = RefinementGuard::TraceFailed;
  const int m = insert_circumcenter(f, refused);
  if (m < 0) {
    grow_failed_to_face_count();
    failed_[f] = {refused, t_.face_area(f)};
    return;
  }
  grow_failed_to_face_count();
  requeue_around(m);
}

void IntrinsicTriangulation::Refinement::grow_failed_to_face_count() {
  if (static_cast<int>(failed_.size()) < t_.face_count())
    failed_.resize(t_.face_count(), {RefinementGuard::TraceFailed, -1.0});
}

// Every face around the new vertex may violate a bound, and every edge of them may be non-Delaunay.
void IntrinsicTriangulation::Refinement::requeue_around(int m) {
  const int first = t_.outgoing_[m];
  for (int h = first, guard = 0; guard < 64; ++guard) {
    const int face = h / 3;
    failed_[face].second = -1.0;
    consider(face);
    for (int i = 0; i < 3; ++i) t_.enqueue_edge(3 * face + i);
    const int n = t_.twin_[prev(h)];
    if (n < 0 || n == first) break;
    h = n;
  }
}

// Inserts the circumcenter of f (or splits the boundary edge in the way); returns the new vertex
// or -1 with the guard that refused.
int IntrinsicTriangulation::Refinement::insert_circumcenter(int f, RefinementGuard& refused) {
  int best = 0;
  double best_angle = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double angle = t_.corner_angle_at(3 * f + i);
    if (angle > best_angle) {
      best_angle = angle;
      best = i;
    }
  }
  // From the corner with the largest angle, the circumcenter direction always lies inside the
  // corner (for an obtuse triangle the circumcenter is beyond the opposite edge).
  const Corners layout = layout_face(t_.length_, f, best);
  const Vector2d center = geometry::circumcenter(layout[0], layout[1], layout[2]);
  const double distance = center.norm();
  if (!(distance > 0.0) || !std::isfinite(distance)) {
    refused = RefinementGuard::TraceFailed;
    return -1;
  }
  const Vector2d direction = center / distance;
  const double raw = std::clamp(direction_angle(direction), 0.0, best_angle);
  const Vector2d ray(std::cos(raw), std::sin(raw));
  const Walk walk = walk_straight(t_.twin_, t_.length_, f, layout, Vector2d::Zero(), ray, distance);
  if (walk.end == Walk::End::Failed) {
    refused = RefinementGuard::TraceFailed;
    return -1;
  }
  const int boundary_hit = boundary_edge_in_the_way(walk);
  if (boundary_hit >= 0) {
    ++result_.boundary_splits;
    return t_.split_boundary_edge(boundary_hit);
  }
  for (const Vector2d& corner : walk.corners)
    if ((corner - walk.point).norm() < kTooCloseFraction * distance) {
      refused = RefinementGuard::InsertionTooClose;
      return -1;
    }
  return insert_inside_walk_face(f, best, best_angle, walk);
}

// The boundary edge to split instead of inserting the walk's end point, or -1: the edge the walk
// stopped at, one the point lies on, or one whose diametral disk holds it.
int IntrinsicTriangulation::Refinement::boundary_edge_in_the_way(const Walk& walk) const {
  int boundary_hit = walk.end == Walk::End::Boundary ? walk.boundary_halfedge : -1;
  if (boundary_hit < 0) {
    // A circumcenter ON a boundary edge (the hypotenuse of a right triangle, up to rounding)
    // counts as outside: inserting it as an interior vertex would make a flat, unflippable face.
    const Vector3d b = geometry::barycentric(walk.corners[0], walk.corners[1], walk.corners[2], walk.point);
    for (int k = 0; k < 3; ++k) {
      const int edge = 3 * walk.face + (k + 1) % 3;  // the edge opposite corner k
      if (t_.twin_[edge] < 0 && b[k] < kOnEdgeBarycentric) boundary_hit = edge;
    }
  }
  if (boundary_hit < 0) boundary_hit = t_.encroached_boundary_edge(walk.face, walk.corners, walk.point);
  return boundary_hit;
}

int IntrinsicTriangulation::Refinement::insert_inside_walk_face(int f, int best, double best_angle, const Walk& walk) {
  // Keep the new vertex strictly inside its face (a point on an edge would make a flat triangle
  // whose area, from rounded lengths, is badly conditioned), then aim the input-mesh trace at the
  // moved point: the walk's plane has the source vertex at the origin and halfedge 3f+best on +x,
  // the frame in which `raw` was measured, so the moved point gives the exact direction and distance.
  Vector3d inside =
      clamped_barycentric(geometry::barycentric(walk.corners[0], walk.corners[1], walk.corners[2], walk.point));
  for (int i = 0; i < 3; ++i) inside[i] = std::max(inside[i], kMinBarycentric);
  inside /= inside.sum();
  const Vector2d target = inside[0] * walk.corners[0] + inside[1] * walk.corners[1] + inside[2] * walk.corners[2];
  const double target_distance = target.norm();
  const double target_raw = std::clamp(direction_angle(target), 0.0, best_angle);
  const int source = t_.tail_[3 * f + best];
  const double source_angle = geometry::wrap_angle(t_.signpost_[3 * f + best] + t_.vertex_scale(source) * target_raw);
  ++result_.circumcenter_insertions;
  return t_.insert_in_face(walk.face, walk.corners, target, target / target_distance, source, source_angle,
                           target_distance);
}

void IntrinsicTriangulation::Refinement::report_skipped_faces() {
  for (int f = 0; f < t_.face_count(); ++f) {
    const Verdict v = verdict(f);
    if (v == Verdict::Fine) continue;
    SkippedFace skipped;
    skipped.face = f;
    skipped.circumradius = t_.face_circumradius(f);
    skipped.min_angle_deg = t_.face_min_angle_deg(f);
    if (v == Verdict::SkipNeedle)
      skipped.guard = RefinementGuard::NeedleVertex;
    else if (v == Verdict::SkipCorner)
      skipped.guard = RefinementGuard::UnimprovableCorner;
    else if (const RefinementGuard* g = failure_of(f))
      skipped.guard = *g;
    else
      skipped.guard = RefinementGuard::Unresolved;
    result_.skipped_faces.push_back(skipped);
  }
}

}  // namespace physarum
