#include "common/maps/map_evaluation.hpp"

#include "common/map_tools/elevation_proxy.hpp"
#include "common/base/errors.hpp"
#include "common/surface/field_transfer.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/map_tools/geodesic_distance.hpp"
#include "common/surface/input_face_overlaps.hpp"
#include "common/map_tools/laplace_interpolation.hpp"
#include "common/maps/map_image.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/map_tools/surface_diffusion.hpp"
#include "common/map_tools/surface_gradient.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace physarum {
namespace {

using Vec3 = Eigen::Vector3d;

// What one map is evaluated against: the surface and, per intrinsic vertex, its input location in
// input coordinates (computed once for all maps).
struct Evaluation {
  const PreparedSurface& surface;
  const std::string& where;
  const EvaluatedMaps& done;  // the maps evaluated so far (every dependency, by the sort)
  const std::vector<Vec3>& vertex_position;
  SurfaceSolvers* solvers;  // kept across the maps of one surface (null where no map is computed)

  const InputMesh& input() const { return surface.input; }
  int vertex_count() const { return surface.domain.vertex_count; }

  [[noreturn]] void fail(const std::string& name, const std::string& problem) const {
    throw InputError(where + ": key 'maps': map '" + name + "': " + problem);
  }

  IntrinsicVertexData<double> operand(const MapOperand& o) const {
    if (const auto* value = std::get_if<double>(&o)) return IntrinsicVertexData<double>(static_cast<size_t>(vertex_count()), *value);
    return done.scalar_map(std::get<std::string>(o));
  }
};

// ---- scalar sources ------------------------------------------------------------------------------

// 1 inside (d <= 0), 0 beyond the falloff, 1 - smoothstep(d / w) between: C1 at both ends.
double region_value(double distance_outside, double falloff) {
  if (distance_outside <= 0.0) return 1.0;
  if (falloff <= 0.0 || distance_outside >= falloff) return 0.0;
  const double t = distance_outside / falloff;
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

// How far `x` lies outside the region (<= 0 inside).
double distance_outside(const RegionSource& r, const Vec3& x) {
  if (const auto* s = std::get_if<SphereRegion>(&r.region)) return (x - s->center).norm() - s->radius;
  if (const auto* b = std::get_if<BoxRegion>(&r.region))
    return (b->min - x).cwiseMax(x - b->max).cwiseMax(0.0).norm();
  if (const auto* s = std::get_if<SegmentsRegion>(&r.region)) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : s->segments) {
      const Vec3 ab = b - a;
      const double length2 = ab.squaredNorm();
      const double t = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (x - a - t * ab).norm());
    }
    return nearest - s->radius;
  }
  const auto& h = std::get<HalfSpaceRegion>(r.region);
  return -(x - h.point).dot(h.normal);
}

// A PLY's vertex property, or InputError naming the map that asked for it.
const std::vector<double>& ply_property(const Evaluation& e, const std::string& name, const PlyFields& ply,
                                        const std::string& property) {
  try {
    return ply.property(property);
  } catch (const InputError& error) {
    e.fail(name, error.what());
  }
}

// The per-input-vertex values of a PLY vertex property. The PLY's vertices are the input mesh's:
// either as loaded (physarum's own outputs: pheromone.ply, maps.ply) or as in the mesh file when
// loading repaired it (dropped unused vertices, split non-manifold ones; InputMesh::file_vertex).
InputVertexData<double> ply_vertex_values(const Evaluation& e, const std::string& name, const PlyVertexSource& s) {
  const PlyFields ply = read_ply_fields(s.path);
  const std::vector<double>& column = ply_property(e, name, ply, s.property);
  const InputMesh& input = e.input();
  InputVertexData<double> values(static_cast<size_t>(input.vertex_count()));
  if (static_cast<int>(column.size()) == input.vertex_count()) {
    std::copy(column.begin(), column.end(), values.begin());
    return values;
  }
  const std::set<int> distinct(input.file_vertex.begin(), input.file_vertex.end());
  const size_t file_vertices = distinct.size() + static_cast<size_t>(input.dropped_unreferenced);
  if (column.size() == file_vertices && !input.file_vertex.empty()) {
    for (int v = 0; v < input.vertex_count(); ++v) values[v] = column[static_cast<size_t>(input.file_vertex[v])];
    return values;
  }
  e.fail(name, s.path + " has " + std::to_string(column.size()) + " vertices, but the input mesh " + input.source +
                   " has " + std::to_string(input.vertex_count()) +
                   (file_vertices != static_cast<size_t>(input.vertex_count())
                        ? " (" + std::to_string(file_vertices) + " in the file)"
                        : std::string()) +
                   ": a PLY map must be on the input mesh's own vertices");
}

// The values of an earlier run's fields_full.ply (common/surface/full_resolution_mesh.hpp: vertex v is
// intrinsic vertex v, placed on the input surface) at this scene's intrinsic vertices, as stored: no
// interpolation, so a cascade's frozen layer holds exactly the first stage's values. Only a run on
// the same surface has the same intrinsic vertices; the count and every position are checked (to a
// millionth of the input's size, as the file stores floats), and another surface is refused.
IntrinsicVertexData<double> fields_full_values(const Evaluation& e, const std::string& name, const FieldsFullSource& s) {
  const PlyFields ply = read_ply_fields(s.path);
  const std::vector<double>& column = ply_property(e, name, ply, s.property);
  const std::string same_surface =
      ": \"fields_full\" reads a run on this scene's own surface (the same mesh, scale_to_area, max_circumradius "
      "and min_angle); for a run on another surface, read its pheromone.ply with {\"ply\": FILE, \"property\": NAME}";
  const int n = e.vertex_count();
  if (static_cast<int>(column.size()) != n)
    e.fail(name, s.path + " has " + std::to_string(column.size()) + " vertices, but this scene's intrinsic triangulation has " +
                     std::to_string(n) + same_surface);
  const InputMesh& input = e.input();
  Vec3 low = input.positions[0], high = input.positions[0];
  for (const Vec3& p : input.positions) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double tolerance = 1e-6 * (high - low).norm();
  for (int v = 0; v < n; ++v) {
    const double off = (ply.mesh.positions[static_cast<size_t>(v)] - e.vertex_position[static_cast<size_t>(v)]).norm();
    if (!(off <= tolerance))
      e.fail(name, s.path + ": vertex " + std::to_string(v) + " lies " + std::to_string(off) +
                       " away from this scene's intrinsic vertex " + std::to_string(v) + same_surface);
  }
  IntrinsicVertexData<double> values(static_cast<size_t>(n));
  std::copy(column.begin(), column.end(), values.begin());
  return values;
}

// The intrinsic vertices a region holds (a Laplace region): where the scalar map `region` is >= 0.5,
// the middle of a region map's 0 outside / 1 inside. The one place a region becomes vertices.
std::vector<int> region_vertices(const Evaluation& e, const std::string& region) {
  const IntrinsicVertexData<double>& values = e.done.scalar_map(region);
  std::vector<int> vertices;
  for (int v = 0; v < e.vertex_count(); ++v)
    if (values[v] >= 0.5) vertices.push_back(v);
  return vertices;
}

// A PLY vertex map at the intrinsic vertices: interpolated linearly in their input faces.
IntrinsicVertexData<double> ply_vertex_map(const Evaluation& e, const std::string& name, const PlyVertexSource& s) {
  const int n = e.vertex_count();
  const SurfaceDomain& domain = e.surface.domain;
  const InputMesh& input = e.input();
  IntrinsicVertexData<double> out(static_cast<size_t>(n));
  const InputVertexData<double> on_input = ply_vertex_values(e, name, s);
  for (int v = 0; v < n; ++v) {
    const SurfacePoint& p = domain.vertex_location[v];
    const auto& t = input.triangles[static_cast<size_t>(p.face)];
    out[v] = p.barycentric[0] * on_input[t[0]] + p.barycentric[1] * on_input[t[1]] + p.barycentric[2] * on_input[t[2]];
  }
  return out;
}

// A texture sampled at the intrinsic vertices' UVs (interpolated in their input faces).
IntrinsicVertexData<double> texture_map(const Evaluation& e, const std::string& name, const TextureSource& s) {
  const int n = e.vertex_count();
  const SurfaceDomain& domain = e.surface.domain;
  const InputMesh& input = e.input();
  IntrinsicVertexData<double> out(static_cast<size_t>(n));
  if (input.uvs.empty())
    e.fail(name, "\"texture\" needs texture coordinates (UVs), and " + input.source + " has none");
  const MapImage image = read_map_image(s.path, s.channel, e.where + ": key 'maps': map '" + name + "'");
  for (int v = 0; v < n; ++v) {
    const SurfacePoint& p = domain.vertex_location[v];
    const auto& t = input.triangle_uvs[static_cast<size_t>(p.face)];
    const Eigen::Vector2d uv =
        p.barycentric[0] * input.uvs[t[0]] + p.barycentric[1] * input.uvs[t[1]] + p.barycentric[2] * input.uvs[t[2]];
    out[v] = image.sample(s.channel, uv);
  }
  return out;
}

// 0 to 1 along one axis of the input mesh's bounding box.
IntrinsicVertexData<double> axis_ramp_map(const Evaluation& e, const std::string& name, const AxisRampSource& s) {
  const int n = e.vertex_count();
  const InputMesh& input = e.input();
  IntrinsicVertexData<double> out(static_cast<size_t>(n));
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Vec3& p : input.positions) low = std::min(low, p[s.axis]), high = std::max(high, p[s.axis]);
  if (!(high > low))
    e.fail(name, std::string("\"axis\": the input mesh is flat along ") + static_cast<char>('x' + s.axis) +
                     " (no ramp along it)");
  // Clamped: an intrinsic vertex lies on the input surface, inside its box up to rounding.
  for (int v = 0; v < n; ++v) out[v] = std::clamp((e.vertex_position[v][s.axis] - low) / (high - low), 0.0, 1.0);
  return out;
}

// The operands folded left to right with the operation.
IntrinsicVertexData<double> combined_map(const Evaluation& e, const CombineSource& s) {
  const int n = e.vertex_count();
  IntrinsicVertexData<double> out = e.operand(s.operands.front());
  for (size_t k = 1; k < s.operands.size(); ++k) {
    const IntrinsicVertexData<double> in = e.operand(s.operands[k]);
    for (int v = 0; v < n; ++v) {
      switch (s.operation) {
        case CombineOperation::Sum: out[v] += in[v]; break;
        case CombineOperation::Product: out[v] *= in[v]; break;
        case CombineOperation::Min: out[v] = std::min(out[v], in[v]); break;
        case CombineOperation::Max: out[v] = std::max(out[v], in[v]); break;
      }
    }
  }
  return out;
}

IntrinsicVertexData<double> laplace_map(const Evaluation& e, const std::string& name, const LaplaceSource& s) {
  std::vector<DirichletRegion> regions;
  for (const LaplaceRegion& r : s.regions) regions.push_back(DirichletRegion{r.region, region_vertices(e, r.region), r.value});
  return laplace_interpolation(e.surface.domain, regions, e.where + ": key 'maps': map '" + name + "'",
                               &e.solvers->laplacian_ordering());
}

void require_finite(const Evaluation& e, const std::string& name, const IntrinsicVertexData<double>& values) {
  for (int v = 0; v < e.vertex_count(); ++v)
    if (!std::isfinite(values[v]))
      e.fail(name, "value " + std::to_string(values[v]) + " at intrinsic vertex " + std::to_string(v) + " is not finite");
}

IntrinsicVertexData<double> evaluate_scalar(const Evaluation& e, const MapDefinition& map) {
  const int n = e.vertex_count();
  const SurfaceDomain& domain = e.surface.domain;
  const InputMesh& input = e.input();
  IntrinsicVertexData<double> out(static_cast<size_t>(n));
  auto pointwise = [&](const MapOperand& operand, auto f) {
    const IntrinsicVertexData<double> in = e.operand(operand);
    for (int v = 0; v < n; ++v) out[v] = f(in[v]);
  };
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, ConstantSource>) {
          out.assign(static_cast<size_t>(n), s.value);
        } else if constexpr (std::is_same_v<S, PlyVertexSource>) {
          out = ply_vertex_map(e, map.name, s);
        } else if constexpr (std::is_same_v<S, FieldsFullSource>) {
          out = fields_full_values(e, map.name, s);
        } else if constexpr (std::is_same_v<S, TextureSource>) {
          out = texture_map(e, map.name, s);
        } else if constexpr (std::is_same_v<S, RegionSource>) {
          for (int v = 0; v < n; ++v) out[v] = region_value(distance_outside(s, e.vertex_position[v]), s.falloff);
        } else if constexpr (std::is_same_v<S, AxisRampSource>) {
          out = axis_ramp_map(e, map.name, s);
        } else if constexpr (std::is_same_v<S, RangeSource>) {
          pointwise(s.operand, [&](double x) { return s.low + (s.high - s.low) * x; });
        } else if constexpr (std::is_same_v<S, InvertSource>) {
          pointwise(s.operand, [](double x) { return 1.0 - x; });
        } else if constexpr (std::is_same_v<S, ThresholdSource>) {
          pointwise(s.operand, [&](double x) { return x >= s.at ? 1.0 : 0.0; });
        } else if constexpr (std::is_same_v<S, ClampSource>) {
          pointwise(s.operand, [&](double x) {
            if (s.low) x = std::max(x, *s.low);
            if (s.high) x = std::min(x, *s.high);
            return x;
          });
        } else if constexpr (std::is_same_v<S, CombineSource>) {
          out = combined_map(e, s);
        } else if constexpr (std::is_same_v<S, GeodesicDistanceSource>) {
          const SeedSurface seeds{domain, e.vertex_position, [&](const std::string& name) -> const IntrinsicVertexData<double>& {
                                    return e.done.scalar_map(name);
                                  }};
          out = geodesic_distance(s, seeds, *e.solvers, e.where + ": key 'maps': map '" + map.name + "'");
        } else if constexpr (std::is_same_v<S, DiffuseSource>) {
          try {
            out = diffuse_on_surface(domain, e.operand(s.operand), s.time, s.steps, &e.solvers->laplacian_ordering());
          } catch (const InputError& error) {
            e.fail(map.name, error.what());
          }
        } else if constexpr (std::is_same_v<S, LaplaceSource>) {
          out = laplace_map(e, map.name, s);
        } else if constexpr (std::is_same_v<S, ElevationSource>) {
          // On the input mesh, then carried to the intrinsic vertices as a PLY vertex map is.
          const ElevationProxy proxy = elevation_proxy(input, s.time, s.steps, e.where + ": key 'maps': map '" + map.name + "'");
          out = input_to_intrinsic(input, domain.vertex_location, proxy.value);
        } else if constexpr (std::is_same_v<S, SlopeSource>) {
          out = gradient_magnitude_per_vertex(domain, e.operand(s.operand));
        } else if constexpr (std::is_same_v<S, DirectionSource> || std::is_same_v<S, RadialSource> ||
                             std::is_same_v<S, PlyFaceVectorSource> || std::is_same_v<S, GradientSource>) {
          throw std::logic_error("map_evaluation: a vector source evaluated as a scalar map");
        } else {
          static_assert(sizeof(S) == 0, "evaluate_scalar: a map source without a case");
        }
      },
      map.source);
  require_finite(e, map.name, out);
  return out;
}

// ---- vector sources ------------------------------------------------------------------------------

// The input faces' 3D vectors of a per-face PLY vector property (one per input triangle).
std::vector<Vec3> ply_face_vectors(const Evaluation& e, const std::string& name, const PlyFaceVectorSource& s) {
  const PlyFields ply = read_ply_fields(s.path);
  std::array<const std::vector<double>*, 3> columns{};
  for (int c = 0; c < 3; ++c) {
    try {
      columns[c] = &ply.face_property(s.property + "_" + static_cast<char>('x' + c));
    } catch (const InputError& error) {
      e.fail(name, error.what());
    }
  }
  const InputMesh& input = e.input();
  if (static_cast<int>(columns[0]->size()) != input.triangle_count())
    e.fail(name, s.path + " has " + std::to_string(columns[0]->size()) + " faces, but the input mesh " + input.source +
                     " has " + std::to_string(input.triangle_count()) +
                     " triangles: a PLY face map must be on the input mesh's own triangles (polygons are split into "
                     "triangles when the mesh is loaded)");
  std::vector<Vec3> vectors(columns[0]->size());
  for (size_t f = 0; f < vectors.size(); ++f) {
    vectors[f] = Vec3((*columns[0])[f], (*columns[1])[f], (*columns[2])[f]);
    if (!vectors[f].allFinite()) e.fail(name, "face " + std::to_string(f) + " of " + s.path + " has a vector that is not finite");
  }
  return vectors;
}

// The closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = va + vb + vc;
  if (!(denominator > 0)) return a;  // a degenerate triangle
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

// For every intrinsic face, the input face nearest to its chord triangle's centroid, among the
// input faces it may overlap.
IntrinsicFaceData<int> input_face_under_centroids(const PreparedSurface& surface, const std::vector<ChordTriangle>& chords) {
  const InputMesh& input = surface.input;
  const InputFaceOverlaps overlaps(input, surface.domain, chords);
  std::vector<std::vector<int>> candidates(chords.size());
  for (int f = 0; f < overlaps.input_face_count(); ++f)
    for (const int t : overlaps.of(f)) candidates[static_cast<size_t>(t)].push_back(f);
  IntrinsicFaceData<int> under(chords.size(), -1);
  for (size_t t = 0; t < chords.size(); ++t) {
    const Vec3 centroid = (chords[t].corner[0] + chords[t].corner[1] + chords[t].corner[2]) / 3.0;
    double best = std::numeric_limits<double>::infinity();
    for (const int f : candidates[t]) {
      const auto& tri = input.triangles[static_cast<size_t>(f)];
      const double d = (closest_point_on_triangle(centroid, input.positions[tri[0]], input.positions[tri[1]],
                                                  input.positions[tri[2]]) - centroid).squaredNorm();
      if (d < best) best = d, under[t] = f;
    }
    if (under[t] < 0) under[t] = chords[t].input_face[0];
  }
  return under;
}

// `d` in the orthonormal frame of chord triangle `chord` (see the header): projected into its plane.
std::array<double, 2> in_chord_frame(const ChordTriangle& chord, const Vec3& d) {
  const Vec3 edge = chord.corner[1] - chord.corner[0];
  const Vec3 normal = edge.cross(chord.corner[2] - chord.corner[0]);
  if (!(edge.norm() > 0.0) || !(normal.norm() > 0.0)) return {0.0, 0.0};  // a degenerate chord: no direction
  const Vec3 x = edge.normalized();
  const Vec3 y = normal.normalized().cross(x);
  return {d.dot(x), d.dot(y)};
}

// The unit direction from `from` toward (or away from) the radial source's point; zero at the point.
Vec3 radial_direction(const RadialSource& s, const Vec3& from) {
  const Vec3 d = s.toward ? Vec3(s.point - from) : Vec3(from - s.point);
  return d.norm() > 0.0 ? Vec3(d.normalized()) : Vec3::Zero();
}

Vec3 projected_into_face(const InputMesh& input, int face, const Vec3& d) {
  const auto& t = input.triangles[static_cast<size_t>(face)];
  const Vec3 normal = (input.positions[t[1]] - input.positions[t[0]]).cross(input.positions[t[2]] - input.positions[t[0]]);
  if (!(normal.norm() > 0.0)) return Vec3::Zero();
  const Vec3 n = normal.normalized();
  return d - d.dot(n) * n;
}

// The chord triangles in INPUT coordinates (the domain's vertex locations refer to the scaled
// mesh, whose triangles are the input's, so the same barycentrics give input positions).
std::vector<ChordTriangle> input_chords(const PreparedSurface& surface) { return chord_triangles(surface.input, surface.domain); }

IntrinsicFaceData<std::array<double, 2>> evaluate_vector(const Evaluation& e, const MapDefinition& map,
                                                         const std::vector<ChordTriangle>& chords,
                                                         const IntrinsicFaceData<int>* under) {
  IntrinsicFaceData<std::array<double, 2>> out(chords.size());
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, DirectionSource>) {
          for (size_t t = 0; t < chords.size(); ++t) out[t] = in_chord_frame(chords[t], s.direction);
        } else if constexpr (std::is_same_v<S, RadialSource>) {
          for (size_t t = 0; t < chords.size(); ++t) {
            const Vec3 centroid = (chords[t].corner[0] + chords[t].corner[1] + chords[t].corner[2]) / 3.0;
            out[t] = in_chord_frame(chords[t], radial_direction(s, centroid));
          }
        } else if constexpr (std::is_same_v<S, PlyFaceVectorSource>) {
          const std::vector<Vec3> vectors = ply_face_vectors(e, map.name, s);
          for (size_t t = 0; t < chords.size(); ++t) out[t] = in_chord_frame(chords[t], vectors[static_cast<size_t>((*under)[t])]);
        } else if constexpr (std::is_same_v<S, GradientSource>) {
          out = gradient_vector_map(e.surface.domain, e.operand(s.operand), s.normalize);  // already in the face frames
        } else {
          throw std::logic_error("map_evaluation: a scalar source evaluated as a vector map");
        }
      },
      map.source);
  return out;
}

}  // namespace

const IntrinsicVertexData<double>& EvaluatedMaps::scalar_map(const std::string& name) const {
  const auto it = scalar.find(name);
  if (it == scalar.end()) throw std::logic_error("EvaluatedMaps: no scalar map '" + name + "'");
  return it->second;
}

const IntrinsicFaceData<std::array<double, 2>>& EvaluatedMaps::vector_map(const std::string& name) const {
  const auto it = vector.find(name);
  if (it == vector.end()) throw std::logic_error("EvaluatedMaps: no vector map '" + name + "'");
  return it->second;
}

EvaluatedMaps evaluate_maps(const MapSet& maps, const PreparedSurface& surface, const std::string& where, EvaluatedMaps known) {
  EvaluatedMaps result = std::move(known);
  if (maps.empty()) return result;
  const SurfaceDomain& domain = surface.domain;
  const InputMesh& input = surface.input;
  std::vector<Vec3> vertex_position(static_cast<size_t>(domain.vertex_count));
  for (int v = 0; v < domain.vertex_count; ++v) {
    const SurfacePoint& p = domain.vertex_location[v];
    const auto& t = input.triangles[static_cast<size_t>(p.face)];
    vertex_position[static_cast<size_t>(v)] =
        p.barycentric[0] * input.positions[t[0]] + p.barycentric[1] * input.positions[t[1]] + p.barycentric[2] * input.positions[t[2]];
  }
  SurfaceSolvers solvers(domain);
  const Evaluation e{surface, where, result, vertex_position, &solvers};

  // The chord triangles and the face location serve every vector map; built only when one exists.
  std::vector<ChordTriangle> chords;
  std::optional<IntrinsicFaceData<int>> under;
  for (const MapDefinition& map : maps.in_dependency_order()) {
    if (result.scalar.count(map.name) || result.vector.count(map.name)) continue;  // known
    if (map.kind == MapKind::Scalar) {
      result.scalar.emplace(map.name, evaluate_scalar(e, map));
      continue;
    }
    if (chords.empty() && !std::holds_alternative<GradientSource>(map.source)) chords = input_chords(surface);
    if (std::holds_alternative<PlyFaceVectorSource>(map.source) && !under) under = input_face_under_centroids(surface, chords);
    result.vector.emplace(map.name, evaluate_vector(e, map, chords, under ? &*under : nullptr));
  }
  return result;
}

InputMaps maps_on_input(const MapSet& maps, const PreparedSurface& surface, const EvaluatedMaps& evaluated,
                        const std::string& where) {
  InputMaps out;
  const InputMesh& input = surface.input;
  const std::vector<Vec3> no_positions;
  const Evaluation e{surface, where, evaluated, no_positions, nullptr};
  for (const MapDefinition& map : maps.in_dependency_order()) {
    if (map.kind == MapKind::Scalar) {
      const IntrinsicVertexData<double>& values = evaluated.scalar_map(map.name);
      InputVertexData<double> on_input(static_cast<size_t>(input.vertex_count()));
      for (int v = 0; v < input.vertex_count(); ++v) on_input[v] = values[surface.input_to_intrinsic[v]];
      out.scalar.emplace_back(map.name, std::move(on_input));
      continue;
    }
    std::vector<Vec3> per_face(static_cast<size_t>(input.triangle_count()));
    if (const auto* d = std::get_if<DirectionSource>(&map.source)) {
      for (int f = 0; f < input.triangle_count(); ++f) per_face[static_cast<size_t>(f)] = projected_into_face(input, f, d->direction);
    } else if (const auto* r = std::get_if<RadialSource>(&map.source)) {
      for (int f = 0; f < input.triangle_count(); ++f) {
        const auto& t = input.triangles[static_cast<size_t>(f)];
        const Vec3 centroid = (input.positions[t[0]] + input.positions[t[1]] + input.positions[t[2]]) / 3.0;
        per_face[static_cast<size_t>(f)] = projected_into_face(input, f, radial_direction(*r, centroid));
      }
    } else if (const auto* g = std::get_if<GradientSource>(&map.source)) {
      // The gradient of the operand's values at the input vertices over each input triangle.
      const IntrinsicVertexData<double>& values = evaluated.scalar_map(std::get<std::string>(g->operand));
      per_face = input_face_gradients(input, intrinsic_to_input(surface.input_to_intrinsic, values), g->normalize);
    } else {
      const std::vector<Vec3> vectors = ply_face_vectors(e, map.name, std::get<PlyFaceVectorSource>(map.source));
      for (int f = 0; f < input.triangle_count(); ++f)
        per_face[static_cast<size_t>(f)] = projected_into_face(input, f, vectors[static_cast<size_t>(f)]);
    }
    out.vector.emplace_back(map.name, std::move(per_face));
  }
  return out;
}

}  // namespace physarum
