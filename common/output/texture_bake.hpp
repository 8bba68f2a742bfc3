#pragma once
// Baking fields onto the input's UV map: a W x H texture in which every texel whose centre lies in
// a UV triangle holds the field at the matching point of the surface, interpolated linearly in the
// intrinsic face that holds that point, so the texture keeps the detail the simulation resolved
// finer than the input triangles (a texture of the input-vertex values could not).
//
// Per texel (locate_texels, done once per mesh and size, then reused for every field and frame):
//  1. Point location through the input face: the input UV triangles are rasterised; the texel
//     centre's barycentric coordinates in the UV triangle that contains it give the point x of the
//     surface in that input face F (in 3D).
//  2. The intrinsic face holding x, among the intrinsic faces that may overlap F (InputFaceOverlaps,
//     built once: a short list per input face, not a global search). Each candidate T is drawn as its
//     CHORD triangle, its three intrinsic vertices at their 3D positions on the surface; x is
//     projected onto each chord triangle's plane, and the texel takes the candidate whose chord
//     triangle contains the projection (barycentrics >= -1e-3) at the least distance from x. When no
//     candidate contains it within 5 % of its size (rounding at edges, or a strongly bent face), the
//     candidate whose chord triangle is nearest to x in 3D is taken, at the nearest point (so the
//     barycentrics are clamped to the triangle).
//  3. The value: the field's three vertex values of T combined with those barycentrics.
// Exactness: a geodesic inside one flat input face is a straight segment, so an intrinsic face lying
// in a flat part of the surface (one input face, or coplanar ones) IS its chord triangle: the
// projection is x itself and the value is exactly the linear interpolant of the intrinsic values
// (up to float storage of the barycentrics, ~1e-7 relative). Where an intrinsic face spans input
// faces at an angle (curved input), the surface bends away from the chord triangle by at most its
// sagitta s (the largest distance of the geodesic triangle from its chord triangle, about
// kappa R^2 / 2 for a face of circumradius R on a surface of curvature kappa); the value is then the
// interpolant at a point within about s of x: for a field with gradient g the error is <= |g| s
// beyond the interpolation error itself, and it vanishes as the triangulation is refined.
//
// Conventions: glTF/OBJ UVs, v = 0 at the BOTTOM of the image; texel (column x, row r) is stored
// with rows top first, as image files are, and its centre is at u = (x + 0.5) / W,
// v = 1 - (r + 0.5) / H. UVs outside [0, 1] WRAP (repeat, glTF's default sampler): a triangle at
// u in [1, 2] lands where u in [0, 1] would, and one crossing u = 1 continues on the left edge. One
// triangle must fit in a single tile (its UVs span at most 1 in u and in v), otherwise one texel
// would stand for several surface points: such a mesh is refused, as are UVs more than 10^4 tiles
// out. Overlapping charts (mirrored halves sharing UVs) give each texel the last input face in file
// order that covers it.
// Work is spread over the host's cores by bands of rows; the result does not depend on how many.
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/output/texture_padding.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace physarum {

// Where a texel lies on the intrinsic triangulation.
struct TexelLocation {
  int face = -1;                       // intrinsic face; -1 when the centre is in no UV triangle
  std::array<float, 3> barycentric{};  // in that face, >= 0, summing to 1
};

struct TexelLocations {
  // Per side. Locating takes 24 bytes per texel (1.6 GB at 8192^2), the result 16 (1.1 GB).
  static constexpr int kMaxSize = 8192;

  int width = 0;
  int height = 0;
  std::vector<TexelLocation> texels;  // row-major, top row first
  // Diagnostics: texels inside a UV triangle, and those that needed the nearest-chord search.
  std::size_t covered_texels = 0;
  std::size_t nearest_search_texels = 0;

  const TexelLocation& at(int x, int row) const { return texels[static_cast<std::size_t>(row) * width + x]; }
};

// Locates every texel of a width x height texture over `mesh`'s UVs. `mesh` is the mesh the
// domain's vertex locations refer to (PreparedSurface::input, or `simulated`: only its triangles, UVs
// and shape matter, not its scale). InputError naming the mesh when it has no UVs ("a texture can
// only be baked onto a UV map"), when a UV is not finite or a triangle spans more than one tile
// (naming the triangle), or when a size is outside 1..kMaxSize.
TexelLocations locate_texels(const InputMesh& mesh, const SurfaceDomain& domain, int width, int height);

// One field to bake, named (the image channel's name).
struct BakeField {
  std::string name;
  const IntrinsicVertexData<double>& values;
};

struct BakeOptions {
  int margin = 16;          // seam padding in texels (texture_padding.hpp); 0 = none
  float background = 0.0f;  // value of the texels outside every chart beyond the margin
};

struct BakedTexture {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // one per field, in the order given
  std::vector<float> values;          // channels.size() floats per texel, row-major, top row first
  std::vector<TexelCoverage> coverage;

  float value(int x, int row, std::size_t channel = 0) const {
    return values[(static_cast<std::size_t>(row) * width + x) * channels.size() + channel];
  }
  TexelCoverage coverage_at(int x, int row) const { return coverage[static_cast<std::size_t>(row) * width + x]; }
};

// Bakes `fields` (at least one, each one value per intrinsic vertex of `domain`, the domain the
// locations were made on) and pads the seams. InputError on a size mismatch or a bad margin.
BakedTexture bake_fields(const TexelLocations& locations, const SurfaceDomain& domain,
                         const std::vector<BakeField>& fields, const BakeOptions& options = {});

}  // namespace physarum
