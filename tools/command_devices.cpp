// `physarum devices`: every OpenCL platform and device, with the index `--device` accepts.
#include "opencl/runtime/device_selection.hpp"
#include "tools/commands.hpp"

#include <cstdio>

namespace physarum::cli {

Command add_devices_command(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand("devices", "List OpenCL platforms and devices (the index is what --device takes)");
  return {app, [] {
            const auto devices = opencl::list_devices();
            if (devices.empty()) {
              std::fprintf(stderr,
                           "physarum: no OpenCL platform or device found (on Debian: apt-get install pocl-opencl-icd)\n");
              return 1;
            }
            for (const auto& d : devices) std::printf("%s\n", d.describe().c_str());
            return 0;
          }};
}

}  // namespace physarum::cli
