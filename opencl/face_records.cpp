#include "opencl/face_records.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <string>

namespace physarum::opencl {

FaceOrder locality_face_order(const SurfaceDomain& domain) {
  const size_t n = static_cast<size_t>(domain.face_count);
  FaceOrder order;
  order.device_of_domain.assign(n, -1);
  order.domain_of_device.reserve(n);
  size_t next_seed = 0;
  for (size_t head = 0; order.domain_of_device.size() < n;) {
    if (head == order.domain_of_device.size()) {  // the queue ran dry: start the next component
      while (order.device_of_domain[next_seed] >= 0) ++next_seed;
      order.device_of_domain[next_seed] = static_cast<int>(order.domain_of_device.size());
      order.domain_of_device.push_back(static_cast<int>(next_seed));
    }
    const int f = order.domain_of_device[head++];
    for (int g : domain.face_neighbour[static_cast<size_t>(f)]) {
      if (g < 0 || order.device_of_domain[static_cast<size_t>(g)] >= 0) continue;
      order.device_of_domain[static_cast<size_t>(g)] = static_cast<int>(order.domain_of_device.size());
      order.domain_of_device.push_back(g);
    }
  }
  return order;
}

VertexOrder locality_vertex_order(const SurfaceDomain& domain, const FaceOrder& faces) {
  const size_t n = static_cast<size_t>(domain.vertex_count);
  VertexOrder order;
  order.device_of_domain.assign(n, -1);
  order.domain_of_device.reserve(n);
  for (int f : faces.domain_of_device)
    for (int v : domain.face_vertices[static_cast<size_t>(f)])
      if (order.device_of_domain[static_cast<size_t>(v)] < 0) {
        order.device_of_domain[static_cast<size_t>(v)] = static_cast<int>(order.domain_of_device.size());
        order.domain_of_device.push_back(v);
      }
  for (size_t v = 0; v < n; ++v)  // vertices on no face (none in a valid domain), kept at the end
    if (order.device_of_domain[v] < 0) {
      order.device_of_domain[v] = static_cast<int>(order.domain_of_device.size());
      order.domain_of_device.push_back(static_cast<int>(v));
    }
  return order;
}

SurfaceDomain renumber_vertices(const SurfaceDomain& domain, const VertexOrder& order) {
  SurfaceDomain d = domain;
  for (auto& corners : d.face_vertices)
    for (int& v : corners) v = order.device_of_domain[static_cast<size_t>(v)];
  for (size_t i = 0; i < order.domain_of_device.size(); ++i) {
    const size_t from = static_cast<size_t>(order.domain_of_device[i]);
    d.vertex_mass[i] = domain.vertex_mass[from];
    d.vertex_location[i] = domain.vertex_location[from];
  }
  // L' = P L P^T: row i' = row of domain vertex domain_of_device[i'], columns renamed.
  const CsrMatrix& L = domain.laplacian;
  CsrMatrix& R = d.laplacian;
  R.row_start.assign(1, 0);
  R.column.clear();
  R.value.clear();
  for (int from : order.domain_of_device) {
    std::vector<std::pair<int, double>> row;
    for (int k = L.row_start[static_cast<size_t>(from)]; k < L.row_start[static_cast<size_t>(from) + 1]; ++k)
      row.emplace_back(order.device_of_domain[static_cast<size_t>(L.column[static_cast<size_t>(k)])],
                       L.value[static_cast<size_t>(k)]);
    std::sort(row.begin(), row.end());
    for (const auto& [column, value] : row) {
      R.column.push_back(column);
      R.value.push_back(value);
    }
    R.row_start.push_back(static_cast<int>(R.column.size()));
  }
  return d;
}

SurfaceDomain in_device_vertex_order(const SurfaceDomain& domain) {
  return renumber_vertices(domain, locality_vertex_order(domain, locality_face_order(domain)));
}

DeviceVertexData<double> to_device_order(const IntrinsicVertexData<double>& domain_values, const VertexOrder& order) {
  DeviceVertexData<double> out(domain_values.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = domain_values[static_cast<size_t>(order.domain_of_device[i])];
  return out;
}

IntrinsicVertexData<double> to_domain_order(const DeviceVertexData<double>& device_values, const VertexOrder& order) {
  IntrinsicVertexData<double> out(device_values.size());
  for (size_t i = 0; i < out.size(); ++i) out[static_cast<size_t>(order.domain_of_device[i])] = device_values[i];
  return out;
}

VertexParameters renumber_parameters(const VertexParameters& params, const VertexOrder& order) {
  VertexParameters renumbered;
  for (const ParameterSpec& p : kParameterTable)
    renumbered[p.id] = IntrinsicVertexData<double>(to_device_order(params[p.id], order).values());
  return renumbered;
}

std::vector<PhysarumFaceRecord> build_face_records(const SurfaceDomain& domain, const FaceOrder& order) {
  std::vector<PhysarumFaceRecord> records(static_cast<size_t>(domain.face_count));
  for (int f = 0; f < domain.face_count; ++f) {
    const size_t uf = static_cast<size_t>(f);
    PhysarumFaceRecord& r = records[static_cast<size_t>(order.device_of_domain[uf])];
    const auto& c = domain.face_corners[uf];
    const double x1 = c[1].x(), x2 = c[2].x(), y2 = c[2].y();
    r.inv_x1 = static_cast<float>(1.0 / x1);
    r.inv_y2 = static_cast<float>(1.0 / y2);
    r.shear = static_cast<float>(x2 / (x1 * y2));
    if (!(static_cast<float>(x1) > 0.0f) || !(static_cast<float>(y2) > 0.0f) || !std::isfinite(r.inv_x1) ||
        !std::isfinite(r.inv_y2) || !std::isfinite(r.shear))
      throw InputError("opencl: intrinsic face " + std::to_string(f) + " is degenerate in float32 (layout x1 = " +
                       std::to_string(c[1].x()) + ", y2 = " + std::to_string(c[2].y()) +
                       "); refine the surface or scale it up");
    r.neighbour_edges = 0;
    for (size_t i = 0; i < 3; ++i) {
      const int g = domain.face_neighbour[uf][i];
      r.neighbour[i] = g < 0 ? -1 : order.device_of_domain[static_cast<size_t>(g)];
      r.vertex[i] = domain.face_vertices[uf][i];
      const Rotation2& t = domain.edge_transition[3 * uf + i];
      r.transition_cos[i] = static_cast<float>(t.cos_angle);
      r.transition_sin[i] = static_cast<float>(t.sin_angle);
      if (g >= 0) r.neighbour_edges |= static_cast<dev_uint>(domain.neighbour_edge[uf][i] & 3) << (2 * i);
    }
  }
  return records;
}

}  // namespace physarum::opencl
