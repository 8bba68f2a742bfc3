#pragma once
// Turning OpenCL status codes into readable errors.
#include "common/base/errors.hpp"

#include <string>

namespace physarum::opencl {

// "CL_OUT_OF_RESOURCES" for -5, and so on; "CL_ERROR(-1234)" for codes it does not know.
std::string error_name(int code);

// A DeviceError whose message is "<what>: <ERROR_NAME> (<code>)" plus a hint for the common cases.
DeviceError device_error(const std::string& what, int code);

}  // namespace physarum::opencl
