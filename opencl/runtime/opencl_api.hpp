#pragma once
// The one place that includes the OpenCL C++ bindings, so every file agrees on the API level:
// OpenCL 1.2 (what every vendor ships), exceptions on, no deprecated 1.1 entry points.
#define CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_TARGET_OPENCL_VERSION 120
#if defined(__GNUC__)
#pragma GCC system_header  // the bindings are third-party code: keep their warnings out of ours
#endif
#include <CL/opencl.hpp>
