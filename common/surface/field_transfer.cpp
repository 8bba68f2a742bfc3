#include "common/surface/field_transfer.hpp"

#include "common/base/errors.hpp"

#include <string>

namespace physarum {
namespace {

// A location sits on a corner of its input face when that barycentric coordinate is 1 up to
// rounding (the triangulation stores input vertices as exact corners; the slack is for safety).
constexpr double kCornerTolerance = 1e-9;

// The corner of `p`'s face it sits on, or -1.
int corner_of(const SurfacePoint& p) {
  for (int c = 0; c < 3; ++c)
    if (p.barycentric[c] >= 1.0 - kCornerTolerance) return c;
  return -1;
}

void check_location(const InputMesh& input, const SurfacePoint& p, size_t intrinsic_vertex) {
  if (p.face < 0 || p.face >= input.triangle_count())
    throw InputError("field transfer: intrinsic vertex " + std::to_string(intrinsic_vertex) + " lies on input face " +
                     std::to_string(p.face) + ", which " + input.source + " does not have");
}

}  // namespace

InputVertexData<int> input_vertex_to_intrinsic(const InputMesh& input,
                                               const IntrinsicVertexData<SurfacePoint>& locations) {
  const int n_input = input.vertex_count();
  InputVertexData<int> map(static_cast<size_t>(n_input), -1);

  // Fast path: the triangulation numbered input vertex v as intrinsic vertex v.
  bool identity = static_cast<int>(locations.size()) >= n_input;
  for (int v = 0; identity && v < n_input; ++v) {
    const SurfacePoint& p = locations[v];
    check_location(input, p, static_cast<size_t>(v));
    const int c = corner_of(p);
    identity = c >= 0 && input.triangles[p.face][c] == v;
  }
  if (identity) {
    for (int v = 0; v < n_input; ++v) map[v] = v;
    return map;
  }

  // General path: every intrinsic vertex sitting on an input corner names its input vertex.
  for (size_t i = 0; i < locations.size(); ++i) {
    check_location(input, locations[i], i);
    const int c = corner_of(locations[i]);
    if (c >= 0) {
      int& slot = map[input.triangles[locations[i].face][c]];
      if (slot < 0) slot = static_cast<int>(i);
    }
  }
  for (int v = 0; v < n_input; ++v)
    if (map[v] < 0)
      throw InputError("field transfer: input vertex " + std::to_string(v) + " of " + input.source +
                       " has no intrinsic vertex on it (the intrinsic triangulation lost an input vertex)");
  return map;
}

InputVertexData<double> intrinsic_to_input(const InputVertexData<int>& map,
                                           const IntrinsicVertexData<double>& intrinsic_values) {
  InputVertexData<double> out(map.size());
  for (size_t v = 0; v < map.size(); ++v) {
    if (map[v] < 0 || static_cast<size_t>(map[v]) >= intrinsic_values.size())
      throw InputError("field transfer: input vertex " + std::to_string(v) + " maps to intrinsic vertex " +
                       std::to_string(map[v]) + " but the field has " + std::to_string(intrinsic_values.size()) +
                       " values");
    out[v] = intrinsic_values[static_cast<size_t>(map[v])];
  }
  return out;
}

InputVertexData<double> intrinsic_to_input(const InputMesh& input, const IntrinsicVertexData<SurfacePoint>& locations,
                                           const IntrinsicVertexData<double>& intrinsic_values) {
  if (intrinsic_values.size() != locations.size())
    throw InputError("field transfer: " + std::to_string(intrinsic_values.size()) + " values for " +
                     std::to_string(locations.size()) + " intrinsic vertices");
  return intrinsic_to_input(input_vertex_to_intrinsic(input, locations), intrinsic_values);
}

IntrinsicVertexData<double> input_to_intrinsic(const InputMesh& input, const IntrinsicVertexData<SurfacePoint>& locations,
                                               const InputVertexData<double>& input_values) {
  if (static_cast<int>(input_values.size()) != input.vertex_count())
    throw InputError("field transfer: " + std::to_string(input_values.size()) + " values for the " +
                     std::to_string(input.vertex_count()) + " vertices of " + input.source);
  IntrinsicVertexData<double> out(locations.size());
  for (size_t i = 0; i < locations.size(); ++i) {
    const SurfacePoint& p = locations[i];
    check_location(input, p, i);
    const auto& t = input.triangles[p.face];
    out[i] = p.barycentric[0] * input_values[t[0]] + p.barycentric[1] * input_values[t[1]] +
             p.barycentric[2] * input_values[t[2]];
  }
  return out;
}

}  // namespace physarum
