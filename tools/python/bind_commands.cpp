// devices() and the command line run in-process (_run_command): the Python tools that are whole
// commands (analyze, compare, colormap) run them as `physarum` does, into a temporary folder, and
// read back what they wrote, so a result from Python is the command's own.
#include "opencl/runtime/device_selection.hpp"
#include "tools/commands.hpp"
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
  m.def(
      "_run_command",
      [](const std::vector<std::string>& args) {
        nb::gil_scoped_release unlocked;
        return cli::run_command_line(args);
      },
      nb::arg("args"));
}

}  // namespace physarum::python
