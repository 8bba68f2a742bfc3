#pragma once
// Per-device choices that change speed, never results, in one table keyed by device type and
// platform (after CLBlast's tuning database, src/database/): the host code asks tuning_for(device)
// instead of testing the device type where it needs a choice. Every entry says why.
#include "opencl/runtime/device_selection.hpp"

namespace physarum::opencl {

struct DeviceTuning {
  // Agents per move walker of one agent_step work-item (kernels/agent_step.cl), 1..4. Above 1 the
  // walks are vector lanes (kernels/lanes.h) and sensing walks 16 rays at once.
  int agents_per_work_item = 1;
  // Build the agent kernels with -DPHYSARUM_CLANG_PREFETCH: clang's __builtin_prefetch instead of
  // OpenCL's prefetch().
  bool clang_prefetch = false;
  // Random-access read-only buffers (face records) in 2 MiB-aligned host memory marked for
  // transparent huge pages (opencl/runtime/device_buffer.hpp).
  bool huge_page_random_access = false;
  // Back-to-back launches per timed device triad (opencl/runtime/memory_bandwidth.hpp).
  int triad_launches = 10;
  // The roofline's bandwidth is the better of the device triad and a triad on the host's threads.
  bool host_triad = false;
  // The largest implicit system (backward-Euler pheromone, IMEX morphogen; unknowns = vertices)
  // that the automatic choice solves with the host's Cholesky factor (opencl/host_cholesky_solve.hpp)
  // rather than the device's conjugate gradients.
  int host_implicit_solve_max_vertices = 0;
};

// The entry of the first row of the table that matches the device (type, then a substring of the
// platform name); the last row matches every device.
DeviceTuning tuning_for(const DeviceInfo& device);

}  // namespace physarum::opencl
