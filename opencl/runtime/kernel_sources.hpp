#pragma once
// The OpenCL C sources of kernels/, embedded into the binary at build time.
#include <string>
#include <vector>

namespace physarum::opencl {

struct EmbeddedFile {
  const char* name;  // file name inside kernels/, e.g. "agent_step.cl"
  const char* text;
};

// Every file of kernels/ (*.cl and *.h), sorted by name. Defined in the generated source.
const std::vector<EmbeddedFile>& embedded_kernel_files();

// The source of kernels/NAME with every `#include "x.h"` of another kernels/ file replaced by that
// file's text (each file at most once), so the OpenCL compiler needs no include path for our own
// headers. System includes (<Random123/...>) are left to the compiler's -I path.
// Throws DeviceError when NAME or an included file is not embedded.
std::string kernel_source(const std::string& name);

}  // namespace physarum::opencl
