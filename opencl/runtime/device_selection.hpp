#pragma once
// Enumerating OpenCL platforms and devices, and choosing one by --device SPEC or PHYSARUM_DEVICE.
#include "common/base/errors.hpp"  // DeviceError, thrown by select_device
#include "opencl/runtime/opencl_api.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace physarum::opencl {

struct DeviceInfo {
  int index = 0;  // position in list_devices(), the number `--device` accepts
  cl::Platform platform;
  cl::Device device;
  std::string platform_name;
  std::string device_name;
  std::string device_version;  // "OpenCL 3.0 PoCL ..."
  std::string driver_version;
  std::string type;            // "CPU", "GPU", "accelerator", "other"
  unsigned compute_units = 0;
  std::uint64_t global_memory_bytes = 0;
  std::uint64_t max_allocation_bytes = 0;
  // The cache in front of global memory as the driver reports it: PoCL gives the CPU's last level;
  // a GPU driver may give its L1s rather than its L2.
  std::uint64_t global_cache_bytes = 0;
  std::size_t max_work_group_size = 0;
  bool int64_atomics = false;  // cl_khr_int64_base_atomics: deposits use 64-bit fixed point

  std::string describe() const;  // one line: "0: Portable Computing Language / pthread-... (CPU, ...)"
};

// Every device of every platform, in a stable order. Empty when no OpenCL platform is installed.
std::vector<DeviceInfo> list_devices();

// spec: "" (then $PHYSARUM_DEVICE, then the first GPU, else the first device), an index into
// list_devices(), or a case-insensitive substring of "platform name / device name".
// Throws DeviceError that lists what was found when nothing matches.
DeviceInfo select_device(const std::string& spec);

}  // namespace physarum::opencl
