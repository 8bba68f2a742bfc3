#include "opencl/runtime/device_tuning.hpp"

#include <array>
#include <limits>
#include <string_view>

namespace physarum::opencl {
namespace {

struct TuningEntry {
  std::string_view type;      // DeviceInfo::type; "" matches every type
  std::string_view platform;  // a substring of DeviceInfo::platform_name; "" matches every platform
  DeviceTuning tuning;
};

// First match wins; the last row is the default.
constexpr std::array kTable = {
    // PoCL's CPU devices:
    //  - 4 agents per work-item: agents moving in the lanes of float4 vectors overlap their chains
    //    of dependent face reads, which a CPU's few threads would otherwise wait on one by one;
    //  - clang's prefetch: PoCL's OpenCL prefetch() compiles to nothing;
    //  - huge pages: random face-record reads across tens of megabytes miss the TLB far less, and
    //    the page walks of 4 KiB pages are dear (in a virtual machine doubly so);
    //  - one triad launch per timing: on a CPU one triad takes milliseconds, launch costs are lost in it;
    //  - the host triad: the device's memory is the host's, and the host's threads may reach more
    //    of its bandwidth than the OpenCL runtime's;
    //  - implicit systems of every size on the host: the field is mapped in place, and one pair of
    //    triangular solves beats the CG's launches at 10^3 vertices and its tens of bandwidth-bound
    //    iterations at 10^6 (bench/README.md, "The implicit solve").
    TuningEntry{"CPU", "Portable Computing Language",
                DeviceTuning{.agents_per_work_item = 4,
                             .clang_prefetch = true,
                             .huge_page_random_access = true,
                             .triad_launches = 1,
                             .host_triad = true,
                             .host_implicit_solve_max_vertices = std::numeric_limits<int>::max()}},
    // Other CPU drivers (Mesa's rusticl on llvmpipe, Intel's CPU runtime): as PoCL's, but with
    // OpenCL's own prefetch(). clang's __builtin_prefetch is a trick of PoCL's compiler; a driver
    // that translates through SPIR-V (rusticl) aborts the process on its llvm.prefetch intrinsic.
    TuningEntry{"CPU", "",
                DeviceTuning{.agents_per_work_item = 1,
                             .clang_prefetch = false,
                             .huge_page_random_access = true,
                             .triad_launches = 1,
                             .host_triad = true,
                             .host_implicit_solve_max_vertices = std::numeric_limits<int>::max()}},
    // Every other device (GPUs, accelerators):
    //  - 1 agent per work-item, scalar walks: a GPU's threads are its lanes already, and idle vector
    //    lanes would only cost instructions;
    //  - OpenCL's own prefetch(); ordinary buffers (device memory is not the host's pages);
    //  - ten triad launches back to back per timing, so a GPU's launch latency does not count;
    //  - no host triad: the device's memory is its own;
    //  - implicit systems on the host only up to 7,000 vertices. Measured on an NVIDIA H200
    //    (`physarum_device_check --only implicit`, 2026-11-27, NVIDIA's OpenCL; the host solve on
    //    that machine's CPU with the field mapped, both copies included): the host factor took
    //    0.053 / 0.19 / 0.85 / 3.3 ms a step at 1,089 / 2,562 / 8,470 / 27,188 vertices, device
    //    CG (2-3 iterations) 0.72 / 0.72 / 0.72 / 0.56 ms, a cost set by its launches and nearly
    //    flat up to 3.4 10^5 vertices (0.51 ms); the two cross near 7,400 vertices. A faster host
    //    CPU moves the crossing up, a slower one down.
    TuningEntry{"", "",
                DeviceTuning{.agents_per_work_item = 1,
                             .clang_prefetch = false,
                             .huge_page_random_access = false,
                             .triad_launches = 10,
                             .host_triad = false,
                             .host_implicit_solve_max_vertices = 7000}},
};

bool matches(const TuningEntry& entry, const DeviceInfo& device) {
  return (entry.type.empty() || entry.type == device.type) &&
         (entry.platform.empty() || device.platform_name.find(entry.platform) != std::string::npos);
}

}  // namespace

DeviceTuning tuning_for(const DeviceInfo& device) {
  for (const TuningEntry& entry : kTable)
    if (matches(entry, device)) return entry.tuning;
  return kTable.back().tuning;
}

}  // namespace physarum::opencl
