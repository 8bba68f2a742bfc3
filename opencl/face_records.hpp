#pragma once
// The surface as the agent kernels read it: one 64-byte PhysarumFaceRecord per intrinsic face
// (kernels/device_types.h), built from the SurfaceDomain's arrays alone. A trace step reads one
// record, i.e. one cache line, instead of gathering corners, neighbours and transitions from five
// arrays.
#include "common/surface_domain.hpp"
#include "kernels/device_types.h"

#include <vector>

namespace physarum::opencl {

static_assert(sizeof(PhysarumFaceRecord) == 64, "PhysarumFaceRecord: sixteen 4-byte fields, one cache line");

// One record per face, in the domain's face order. Throws InputError when a face is degenerate in
// float32 (its layout must have x1 > 0 and y2 > 0 after rounding).
std::vector<PhysarumFaceRecord> build_face_records(const SurfaceDomain& domain);

}  // namespace physarum::opencl
