#include "opencl/runtime/device_selection.hpp"

#include "opencl/runtime/opencl_error.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

namespace physarum::opencl {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  return s;
}

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_GPU) return "GPU";
  if (t & CL_DEVICE_TYPE_CPU) return "CPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::string found_list(const std::vector<DeviceInfo>& devices) {
  if (devices.empty()) return "no OpenCL platform or device was found (on Debian: apt-get install pocl-opencl-icd)";
  std::string s = "devices found:";
  for (const DeviceInfo& d : devices) s += "\n  " + d.describe();
  return s;
}

}  // namespace

std::string DeviceInfo::describe() const {
  std::ostringstream os;
  os << index << ": " << platform_name << " / " << device_name << " (" << type << ", " << compute_units
     << " compute units, " << (global_memory_bytes >> 20) << " MiB, max allocation " << (max_allocation_bytes >> 20)
     << " MiB, cache " << (global_cache_bytes >> 10) << " KiB, " << device_version << ", driver " << driver_version
     << (int64_atomics ? ", 64-bit atomics" : ", no 64-bit atomics") << ")";
  return os.str();
}

std::vector<DeviceInfo> list_devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    if (e.err() == -1001 /* CL_PLATFORM_NOT_FOUND_KHR */) return {};
    throw device_error("listing OpenCL platforms", e.err());
  }
  std::vector<DeviceInfo> out;
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error& e) {
      if (e.err() == CL_DEVICE_NOT_FOUND) continue;  // a platform with nothing usable
      throw device_error("listing devices of an OpenCL platform", e.err());
    }
    for (const cl::Device& device : devices) {
      DeviceInfo d;
      d.index = static_cast<int>(out.size());
      d.platform = platform;
      d.device = device;
      d.platform_name = trimmed(platform.getInfo<CL_PLATFORM_NAME>());
      d.device_name = trimmed(device.getInfo<CL_DEVICE_NAME>());
      d.device_version = trimmed(device.getInfo<CL_DEVICE_VERSION>());
      d.driver_version = trimmed(device.getInfo<CL_DRIVER_VERSION>());
      d.type = type_name(device.getInfo<CL_DEVICE_TYPE>());
      d.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      d.global_memory_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      d.max_allocation_bytes = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      d.global_cache_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_CACHE_SIZE>();
      d.max_work_group_size = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
      const std::string extensions = device.getInfo<CL_DEVICE_EXTENSIONS>();
      d.int64_atomics = extensions.find("cl_khr_int64_base_atomics") != std::string::npos;
      out.push_back(std::move(d));
    }
  }
  return out;
}

DeviceInfo select_device(const std::string& spec_in) {
  const std::vector<DeviceInfo> devices = list_devices();
  std::string spec = spec_in;
  std::string origin = "--device";
  if (spec.empty()) {
    if (const char* env = std::getenv("PHYSARUM_DEVICE"); env && *env) {
      spec = env;
      origin = "PHYSARUM_DEVICE";
    }
  }
  if (devices.empty()) throw DeviceError(found_list(devices));
  if (spec.empty()) {
    for (const DeviceInfo& d : devices)
      if (d.type == "GPU") return d;
    return devices.front();
  }
  if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
    const long index = std::strtol(spec.c_str(), nullptr, 10);
    if (index >= 0 && index < static_cast<long>(devices.size())) return devices[static_cast<size_t>(index)];
    throw DeviceError(origin + " " + spec + ": there is no device with that index; " + found_list(devices));
  }
  const std::string needle = lower(spec);
  for (const DeviceInfo& d : devices)
    if (lower(d.platform_name + " / " + d.device_name).find(needle) != std::string::npos) return d;
  throw DeviceError(origin + " '" + spec + "' matches no platform or device name; " + found_list(devices));
}

}  // namespace physarum::opencl
