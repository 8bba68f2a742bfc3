#pragma once
// The surface as the agent kernels read it: one 64-byte PhysarumFaceRecord per intrinsic face
// (kernels/device_types.h), built from the SurfaceDomain's arrays alone. A trace step reads one
// record, i.e. one cache line, instead of gathering corners, neighbours and transitions from five
// arrays.
//
// Records are stored in a locality order, not the domain's: faces that refinement appended at the
// end of the domain's list sit far from their neighbours there, so a walk would touch a new cache
// line (or page) at every crossing. A breadth-first order over face adjacency keeps neighbours a
// ring apart (~sqrt(F) records, like Cuthill-McKee), and agents sorted by device face then walk
// through memory that their neighbours in the agent arrays have just brought into cache.
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"
#include "common/model/vertex_parameters.hpp"
#include "kernels/device_types.h"

#include <vector>

namespace physarum::opencl {

static_assert(sizeof(PhysarumFaceRecord) == 64, "PhysarumFaceRecord: sixteen 4-byte fields, one cache line");

struct FaceOrder {
  std::vector<int> device_of_domain;  // device face index of each domain face
  std::vector<int> domain_of_device;  // and back
};

// Breadth-first order over face adjacency, restarted at the lowest unvisited face for every
// connected component; a permutation of 0..F-1.
FaceOrder locality_face_order(const SurfaceDomain& domain);

// Vertices in the order the faces (in `faces` order) first touch them: the concentration a sensor
// reads and the deposits an agent makes then land near the face records it just read, instead of
// wherever the input file or the refinement happened to number the vertex.
struct VertexOrder {
  std::vector<int> device_of_domain;
  std::vector<int> domain_of_device;
};
VertexOrder locality_vertex_order(const SurfaceDomain& domain, const FaceOrder& faces);

// The domain with its vertices renumbered (face vertices, masses, locations, Laplacian rows and
// columns); faces keep their domain order. What the device's pheromone field is built from.
SurfaceDomain renumber_vertices(const SurfaceDomain& domain, const VertexOrder& order);

// The domain numbered as OpenCLAgentSimulation numbers it for its pheromone field (the locality vertex
// order of the locality face order): what a benchmark of the device's pheromone step alone uses, so
// it reads memory the way a simulation's does.
SurfaceDomain in_device_vertex_order(const SurfaceDomain& domain);

// Per-vertex values between the two numberings.
DeviceVertexData<double> to_device_order(const IntrinsicVertexData<double>& domain_values, const VertexOrder& order);
IntrinsicVertexData<double> to_domain_order(const DeviceVertexData<double>& device_values, const VertexOrder& order);

// The parameter maps renumbered like renumber_vertices' domain: what the device buffers are built
// from, beside that domain (held in the domain's own types, as the renumbered domain is).
VertexParameters renumber_parameters(const VertexParameters& params, const VertexOrder& order);

// One record per face, in device order (neighbour indices are device indices too). Throws
// InputError when a face is degenerate in float32 (its layout must have x1 > 0 and y2 > 0).
std::vector<PhysarumFaceRecord> build_face_records(const SurfaceDomain& domain, const FaceOrder& order);

}  // namespace physarum::opencl
