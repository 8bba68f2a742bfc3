#include "common/output/texture_bake.hpp"

#include "common/base/errors.hpp"
#include "common/surface/chord_geometry.hpp"
#include "common/surface/full_resolution_mesh.hpp"
#include "common/surface/input_face_overlaps.hpp"
#include "common/base/parallel_chunks.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>

namespace physarum {
namespace {

// A texel centre on a UV triangle's edge counts as inside down to this barycentric: neighbouring
// triangles then both claim a centre on their shared edge (the later one keeps it) instead of both
// missing it through rounding.
constexpr double kUvInsideSlack = 1e-9;
// UVs may wrap this many tiles away from [0, 1], no farther.
constexpr double kFarthestTile = 10000.0;
// How many candidates ahead their chord triangles are prefetched.
constexpr size_t kPrefetchAhead = 8;

std::string describe_uv(const Eigen::Vector2d& uv) { return "(" + std::to_string(uv.x()) + ", " + std::to_string(uv.y()) + ")"; }

void check_uvs(const InputMesh& mesh) {
  if (mesh.uvs.empty() || mesh.triangle_uvs.size() != mesh.triangles.size())
    throw InputError(mesh.source + " has no texture coordinates (UVs): a texture can only be baked onto a UV map");
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    Eigen::Vector2d low = Eigen::Vector2d::Constant(HUGE_VAL), high = -low;
    for (int c = 0; c < 3; ++c) {
      const int i = mesh.triangle_uvs[t][c];
      if (i < 0 || i >= static_cast<int>(mesh.uvs.size()))
        throw InputError(mesh.source + ": triangle " + std::to_string(t) + " names texture coordinate " +
                         std::to_string(i) + ", which does not exist");
      const Eigen::Vector2d& uv = mesh.uvs[static_cast<size_t>(i)];
      if (!uv.allFinite())
        throw InputError(mesh.source + ": triangle " + std::to_string(t) + " has a texture coordinate that is not finite");
      // Texel coordinates (UV times the size) must stay far inside int range, and wrapping a UV
      // that far out would have lost its fraction to rounding anyway.
      if (uv.cwiseAbs().maxCoeff() > kFarthestTile)
        throw InputError(mesh.source + ": triangle " + std::to_string(t) + " has texture coordinate " + describe_uv(uv) +
                         ", more than " + std::to_string(static_cast<int>(kFarthestTile)) + " tiles from [0, 1]");
      low = low.cwiseMin(uv);
      high = high.cwiseMax(uv);
    }
    if ((high - low).maxCoeff() > 1.0 + 1e-9)
      throw InputError(mesh.source + ": triangle " + std::to_string(t) + " spans more than one texture tile (UVs " +
                       describe_uv(low) + " to " + describe_uv(high) +
                       "); UVs may lie outside [0, 1] and wrap, but a baked texel must stand for one surface point");
  }
}

// One input face as rasterised: its UV corners in texel units (x = u W, y = v H, y up, not wrapped),
// the texel centres (i + 0.5, j + 0.5) it may cover, and its barycentric coordinates as a function
// of the texel centre.
struct UvTriangle {
  Eigen::Vector2d q0, e1, e2;
  double inverse_area2 = 0.0;  // 1 / cross(e1, e2); 0 for a triangle of no area (covers nothing)
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;

  bool empty() const { return inverse_area2 == 0.0 || i1 < i0 || j1 < j0; }
  // Barycentric coordinates of the centre of texel (i, j).
  Eigen::Vector3d barycentric(int i, int j) const {
    const double dx = i + 0.5 - q0.x(), dy = j + 0.5 - q0.y();
    const double l1 = (dx * e2.y() - dy * e2.x()) * inverse_area2;
    const double l2 = (e1.x() * dy - e1.y() * dx) * inverse_area2;
    return {1.0 - l1 - l2, l1, l2};
  }
};

UvTriangle uv_triangle(const InputMesh& mesh, int face, int width, int height) {
  UvTriangle t;
  std::array<Eigen::Vector2d, 3> q;
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector2d& uv = mesh.uvs[static_cast<size_t>(mesh.triangle_uvs[face][c])];
    q[c] = {uv.x() * width, uv.y() * height};
  }
  t.q0 = q[0];
  t.e1 = q[1] - q[0];
  t.e2 = q[2] - q[0];
  const double area2 = t.e1.x() * t.e2.y() - t.e1.y() * t.e2.x();
  if (!(std::abs(area2) > 1e-12)) return t;
  t.inverse_area2 = 1.0 / area2;
  const Eigen::Vector2d low = q[0].cwiseMin(q[1]).cwiseMin(q[2]), high = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
  t.i0 = static_cast<int>(std::ceil(low.x() - 0.5));
  t.i1 = static_cast<int>(std::floor(high.x() - 0.5));
  t.j0 = static_cast<int>(std::ceil(low.y() - 0.5));
  t.j1 = static_cast<int>(std::floor(high.y() - 0.5));
  return t;
}

int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

std::array<float, 3> clamped(const Eigen::Vector3d& beta) {
  const Eigen::Vector3d b = beta.cwiseMax(0.0);
  const double sum = b.sum();
  if (!(sum > 0.0)) return {1.0f, 0.0f, 0.0f};
  return {static_cast<float>(b[0] / sum), static_cast<float>(b[1] / sum), static_cast<float>(b[2] / sum)};
}

// A convex polygon of at most 6 corners (a triangle clipped by three half-planes), kept on the stack:
// it is made once per (input face, intrinsic face) pair, millions of times.
struct SmallPolygon {
  std::array<Eigen::Vector2d, 6> corner;
  int size = 0;
};

// The part of the UV triangle (in its barycentric coordinates l1, l2; l0 = 1 - l1 - l2) where the
// affine functions g_m(l) = sum_k l_k B[k][m] + kChordSlack are all >= 0: Sutherland-Hodgman
// clipping of the triangle by three half-planes (empty when nothing is left).
SmallPolygon clip_footprint(const std::array<Eigen::Vector3d, 3>& B) {
  SmallPolygon polygon, next;
  polygon.corner[0] = {0, 0};
  polygon.corner[1] = {1, 0};
  polygon.corner[2] = {0, 1};
  polygon.size = 3;
  for (int m = 0; m < 3 && polygon.size > 0; ++m) {
    auto g = [&](const Eigen::Vector2d& l) {
      return (1.0 - l.x() - l.y()) * B[0][m] + l.x() * B[1][m] + l.y() * B[2][m] + kChordSlack;
    };
    next.size = 0;
    for (int i = 0; i < polygon.size; ++i) {
      const Eigen::Vector2d& p = polygon.corner[static_cast<size_t>(i)];
      const Eigen::Vector2d& q = polygon.corner[static_cast<size_t>((i + 1) % polygon.size)];
      const double gp = g(p), gq = g(q);
      // Each half-plane adds at most one corner to a convex polygon: 3 + 3 = 6 at most.
      if (gp >= 0.0 && next.size < 6) next.corner[static_cast<size_t>(next.size++)] = p;
      if ((gp >= 0.0) != (gq >= 0.0) && next.size < 6)
        next.corner[static_cast<size_t>(next.size++)] = p + (q - p) * (gp / (gp - gq));
    }
    polygon = next;
  }
  return polygon;
}

// locate_texels' work, in bands of rows (top first), each band processed whole by one thread: the
// three passes over the input faces that reach into a band, and what they share.
class TexelBands {
 public:
  TexelBands(const InputMesh& mesh, const std::vector<ChordTriangle>& chords, const InputFaceOverlaps& overlaps,
             TexelLocations& out)
      : mesh_(mesh), chords_(chords), overlaps_(overlaps), out_(out), width_(out.width), height_(out.height),
        band_count_(std::min(height_, 8 * parallel_worker_count())) {
    const size_t texels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    out_.texels.assign(texels, TexelLocation{});
    owner_.assign(texels, -1);
    best_.assign(texels, std::numeric_limits<float>::infinity());
    uv_.resize(static_cast<size_t>(mesh.triangle_count()));
    for (int f = 0; f < mesh.triangle_count(); ++f) uv_[static_cast<size_t>(f)] = uv_triangle(mesh, f, width_, height_);
    collect_band_faces();
    covered_.assign(static_cast<size_t>(band_count_), 0);
    searched_.assign(static_cast<size_t>(band_count_), 0);
  }

  int band_count() const { return band_count_; }

  void locate(int band) {
    const std::vector<int>& faces = band_faces_[static_cast<size_t>(band)];
    for (const int f : faces) assign_owners(band, f);
    for (const int f : faces) {
      paint_footprints(band, f);
      search_nearest(band, f);
    }
    for (int row = 0; row < height_; ++row)
      if (band_of_row(row) == band)
        for (int x = 0; x < width_; ++x) covered_[static_cast<size_t>(band)] += owner_[static_cast<size_t>(row) * width_ + x] >= 0;
  }

  void add_counts() {
    for (int b = 0; b < band_count_; ++b) {
      out_.covered_texels += covered_[static_cast<size_t>(b)];
      out_.nearest_search_texels += searched_[static_cast<size_t>(b)];
    }
  }

 private:
  int band_of_row(int row) const { return static_cast<int>(static_cast<long long>(row) * band_count_ / height_); }
  int row_of(int j) const { return height_ - 1 - wrap(j, height_); }
  size_t texel_index(int i, int j) const {
    return static_cast<size_t>(row_of(j)) * static_cast<size_t>(width_) + static_cast<size_t>(wrap(i, width_));
  }

  // The faces that reach into each band.
  void collect_band_faces() {
    band_faces_.resize(static_cast<size_t>(band_count_));
    for (int f = 0; f < mesh_.triangle_count(); ++f) {
      const UvTriangle& t = uv_[static_cast<size_t>(f)];
      if (t.empty()) continue;
      int last_band = -1;
      std::vector<char> seen;  // only for faces spanning the image height, which may revisit bands
      for (int j = t.j0; j <= t.j1; ++j) {
        const int band = band_of_row(row_of(j));
        if (band == last_band) continue;
        if (t.j1 - t.j0 + 1 > height_ / band_count_) {
          if (seen.empty()) seen.assign(static_cast<size_t>(band_count_), 0);
          if (seen[static_cast<size_t>(band)]) continue;
          seen[static_cast<size_t>(band)] = 1;
        }
        band_faces_[static_cast<size_t>(band)].push_back(f);
        last_band = band;
      }
    }
  }

  // 1. Which input face holds each texel centre (the later face on shared edges).
  void assign_owners(int band, int f) {
    const UvTriangle& t = uv_[static_cast<size_t>(f)];
    for (int j = t.j0; j <= t.j1; ++j) {
      if (band_of_row(row_of(j)) != band) continue;
      for (int i = t.i0; i <= t.i1; ++i)
        if (t.barycentric(i, j).minCoeff() >= -kUvInsideSlack) owner_[texel_index(i, j)] = f;
    }
  }

  // 2. Each candidate intrinsic face paints the texels of its footprint on input face f; the
  // nearest containing chord triangle wins.
  void paint_footprints(int band, int f) {
    const UvTriangle& t = uv_[static_cast<size_t>(f)];
    const std::array<Eigen::Vector3d, 3> P = corners_of(f);
    const std::span<const int> candidates = overlaps_.of(f);
    for (size_t n = 0; n < candidates.size(); ++n) {
      // The candidates' chords are scattered over memory (intrinsic faces are numbered in
      // insertion order): fetching a few ahead hides most of the wait for them.
      if (n + kPrefetchAhead < candidates.size())
        __builtin_prefetch(&chords_[static_cast<size_t>(candidates[n + kPrefetchAhead])]);
      const int T = candidates[n];
      const auto& corner = chords_[static_cast<size_t>(T)].corner;
      const Chord chord(corner[0], corner[1], corner[2]);
      if (chord.degenerate) continue;
      std::array<Eigen::Vector3d, 3> B;
      Eigen::Vector3d D;
      for (int k = 0; k < 3; ++k) {
        B[k] = chord.barycentric(P[k]);
        D[k] = chord.signed_distance(P[k]);
      }
      const SmallPolygon footprint = clip_footprint(B);
      if (footprint.size == 0) continue;
      Eigen::Vector2d low = Eigen::Vector2d::Constant(HUGE_VAL), high = -low;
      for (int c = 0; c < footprint.size; ++c) {
        const Eigen::Vector2d& l = footprint.corner[static_cast<size_t>(c)];
        const Eigen::Vector2d q = t.q0 + l.x() * t.e1 + l.y() * t.e2;
        low = low.cwiseMin(q);
        high = high.cwiseMax(q);
      }
      const int i0 = std::max(t.i0, static_cast<int>(std::ceil(low.x() - 0.5)) - 1);
      const int i1 = std::min(t.i1, static_cast<int>(std::floor(high.x() - 0.5)) + 1);
      const int j0 = std::max(t.j0, static_cast<int>(std::ceil(low.y() - 0.5)) - 1);
      const int j1 = std::min(t.j1, static_cast<int>(std::floor(high.y() - 0.5)) + 1);
      for (int j = j0; j <= j1; ++j) {
        if (band_of_row(row_of(j)) != band) continue;
        for (int i = i0; i <= i1; ++i) {
          const size_t index = texel_index(i, j);
          if (owner_[index] != f) continue;
          const Eigen::Vector3d l = t.barycentric(i, j);
          const Eigen::Vector3d beta = l[0] * B[0] + l[1] * B[1] + l[2] * B[2];
          const double outside = -beta.minCoeff();
          if (outside > kChordSlack) continue;
          const double score = std::abs(l.dot(D)) + chord.longest_edge * std::max(0.0, outside);
          if (score >= best_[index]) continue;
          best_[index] = static_cast<float>(score);
          out_.texels[index] = TexelLocation{T, clamped(beta)};
        }
      }
    }
  }

  // 3. Texels of input face f left without an acceptable candidate: the nearest chord triangle.
  void search_nearest(int band, int f) {
    const UvTriangle& t = uv_[static_cast<size_t>(f)];
    const std::array<Eigen::Vector3d, 3> P = corners_of(f);
    auto surface_point = [&](const Eigen::Vector3d& l) {
      const Eigen::Vector3d c = l.cwiseMax(0.0) / l.cwiseMax(0.0).sum();
      return Eigen::Vector3d(c[0] * P[0] + c[1] * P[1] + c[2] * P[2]);
    };
    for (int j = t.j0; j <= t.j1; ++j) {
      if (band_of_row(row_of(j)) != band) continue;
      for (int i = t.i0; i <= t.i1; ++i) {
        const size_t index = texel_index(i, j);
        if (owner_[index] != f) continue;
        TexelLocation& location = out_.texels[index];
        if (location.face >= 0) {
          const auto& corner = chords_[static_cast<size_t>(location.face)].corner;
          const double size = std::max({(corner[1] - corner[0]).norm(), (corner[2] - corner[1]).norm(),
                                        (corner[0] - corner[2]).norm()});
          if (best_[index] <= kAcceptableDistance * size) continue;
        }
        const Eigen::Vector3d x = surface_point(t.barycentric(i, j));
        double nearest = HUGE_VAL;
        for (const int T : overlaps_.of(f)) {
          const auto& corner = chords_[static_cast<size_t>(T)].corner;
          const Eigen::Vector3d &a = corner[0], &b = corner[1], &c = corner[2];
          const auto [beta, distance2] = nearest_on_triangle(x, a, b, c, Chord(a, b, c));
          if (distance2 < nearest) {
            nearest = distance2;
            location = TexelLocation{T, clamped(beta)};
          }
        }
        ++searched_[static_cast<size_t>(band)];
      }
    }
  }

  std::array<Eigen::Vector3d, 3> corners_of(int f) const {
    const auto& corners = mesh_.triangles[static_cast<size_t>(f)];
    return {mesh_.positions[corners[0]], mesh_.positions[corners[1]], mesh_.positions[corners[2]]};
  }

  const InputMesh& mesh_;
  const std::vector<ChordTriangle>& chords_;
  const InputFaceOverlaps& overlaps_;
  TexelLocations& out_;
  const int width_, height_, band_count_;
  std::vector<UvTriangle> uv_;
  std::vector<int> owner_;   // the input face whose UV triangle holds the texel centre
  std::vector<float> best_;  // the winning candidate's score per texel
  std::vector<std::vector<int>> band_faces_;
  std::vector<size_t> covered_, searched_;  // per band
};

}  // namespace

TexelLocations locate_texels(const InputMesh& mesh, const SurfaceDomain& domain, int width, int height) {
  if (width < 1 || height < 1 || width > TexelLocations::kMaxSize || height > TexelLocations::kMaxSize)
    throw InputError("texture of " + mesh.source + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is out of range (1.." + std::to_string(TexelLocations::kMaxSize) + " each)");
  check_uvs(mesh);
  const std::vector<ChordTriangle> chords = chord_triangles(mesh, domain);
  const InputFaceOverlaps overlaps(mesh, domain, chords);
  TexelLocations out;
  out.width = width;
  out.height = height;
  TexelBands bands(mesh, chords, overlaps, out);
  parallel_chunks(bands.band_count(), [&](int band) { bands.locate(band); });
  bands.add_counts();
  return out;
}

BakedTexture bake_fields(const TexelLocations& locations, const SurfaceDomain& domain,
                         const std::vector<BakeField>& fields, const BakeOptions& options) {
  if (fields.empty()) throw InputError("texture bake: no field to bake");
  for (const BakeField& field : fields)
    if (static_cast<int>(field.values.size()) != domain.vertex_count)
      throw InputError("texture bake: field " + field.name + " has " + std::to_string(field.values.size()) +
                       " values for " + std::to_string(domain.vertex_count) + " intrinsic vertices");
  if (options.margin < 0) throw InputError("texture bake: margin " + std::to_string(options.margin) + " must be >= 0");

  BakedTexture out;
  out.width = locations.width;
  out.height = locations.height;
  for (const BakeField& field : fields) out.channels.push_back(field.name);
  const size_t channels = fields.size();
  const size_t texels = locations.texels.size();
  out.values.assign(texels * channels, 0.0f);
  out.coverage.assign(texels, TexelCoverage::Background);

  const int chunk_count = std::max(1, std::min(locations.height, 8 * parallel_worker_count()));
  parallel_chunks(chunk_count, [&](int chunk) {
    const size_t begin = texels * static_cast<size_t>(chunk) / static_cast<size_t>(chunk_count);
    const size_t end = texels * (static_cast<size_t>(chunk) + 1) / static_cast<size_t>(chunk_count);
    for (size_t t = begin; t < end; ++t) {
      const TexelLocation& location = locations.texels[t];
      if (location.face < 0) continue;
      out.coverage[t] = TexelCoverage::Chart;
      const auto& v = domain.face_vertices[static_cast<size_t>(location.face)];
      for (size_t c = 0; c < channels; ++c) {
        const IntrinsicVertexData<double>& f = fields[c].values;
        out.values[t * channels + c] =
            static_cast<float>(location.barycentric[0] * f[static_cast<size_t>(v[0])] +
                               location.barycentric[1] * f[static_cast<size_t>(v[1])] +
                               location.barycentric[2] * f[static_cast<size_t>(v[2])]);
      }
    }
  });
  pad_charts(out.width, out.height, static_cast<int>(channels), out.values, out.coverage, options.margin,
             options.background);
  return out;
}

}  // namespace physarum
