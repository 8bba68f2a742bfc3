#include "opencl/face_records.hpp"

#include "common/errors.hpp"

#include <string>

namespace physarum::opencl {

std::vector<PhysarumFaceRecord> build_face_records(const SurfaceDomain& domain) {
  std::vector<PhysarumFaceRecord> records(static_cast<size_t>(domain.face_count));
  for (int f = 0; f < domain.face_count; ++f) {
    PhysarumFaceRecord& r = records[static_cast<size_t>(f)];
    const auto& c = domain.face_corners[static_cast<size_t>(f)];
    r.x1 = static_cast<float>(c[1].x());
    r.x2 = static_cast<float>(c[2].x());
    r.y2 = static_cast<float>(c[2].y());
    if (!(r.x1 > 0.0f) || !(r.y2 > 0.0f))
      throw InputError("opencl: intrinsic face " + std::to_string(f) +
                       " is degenerate in float32 (layout x1 = " + std::to_string(c[1].x()) +
                       ", y2 = " + std::to_string(c[2].y()) + "); refine the surface or scale it up");
    r.neighbour_edges = 0;
    for (int i = 0; i < 3; ++i) {
      const int g = domain.face_neighbour[static_cast<size_t>(f)][static_cast<size_t>(i)];
      r.neighbour[i] = g;
      r.vertex[i] = domain.face_vertices[static_cast<size_t>(f)][static_cast<size_t>(i)];
      const Rigid2& t = domain.edge_transition[static_cast<size_t>(3 * f + i)];
      r.transition_cos[i] = static_cast<float>(t.cos_angle);
      r.transition_sin[i] = static_cast<float>(t.sin_angle);
      if (g >= 0)
        r.neighbour_edges |= static_cast<dev_uint>(domain.neighbour_edge[static_cast<size_t>(f)][static_cast<size_t>(i)] & 3)
                             << (2 * i);
    }
  }
  return records;
}

}  // namespace physarum::opencl
