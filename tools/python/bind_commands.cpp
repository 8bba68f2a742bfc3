// devices(): the OpenCL devices as `physarum devices` lists them.
#include "opencl/runtime/device_selection.hpp"
#include "tools/python/bindings.hpp"

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

namespace physarum::python {

void bind_commands(nb::module_& m) {
  m.def(
      "devices",
      [] {
        nb::list out;
        for (const opencl::DeviceInfo& d : opencl::list_devices()) {
          nb::dict device;
          device["index"] = d.index;
          device["platform"] = d.platform_name;
          device["name"] = d.device_name;
          device["type"] = d.type;
          device["version"] = d.device_version;
          device["driver"] = d.driver_version;
          device["compute_units"] = d.compute_units;
          device["global_memory_bytes"] = d.global_memory_bytes;
          device["description"] = d.describe();
          out.append(device);
        }
        return out;
      },
      "The OpenCL devices, as `physarum devices` lists them: a list of dicts (index: what device= takes).");
}

}  // namespace physarum::python
