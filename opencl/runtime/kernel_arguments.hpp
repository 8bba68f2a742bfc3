#pragma once
// All of a kernel's arguments in one typed call, in the order of the kernel's parameter list:
//
//   set_arguments(kernel, n, row_start, column, value, x, y, cl::Local(group * sizeof(cl_float4)));
//
// (after CLBlast's Kernel::SetArguments, src/clpp11.hpp). No index is written by hand, so an
// argument cannot land at the wrong position or be left out silently. Accepted: DeviceBuffer and
// cl::Buffer (a buffer argument), cl::LocalSpaceArg (local memory), a BufferList (several buffer
// arguments in a row, e.g. every agent array) and any trivially copyable value (scalars, vector
// types, the structs of kernels/device_types.h). When the kernel's own count of parameters
// (CL_KERNEL_NUM_ARGS) is to be checked as well, use set_arguments_checked: one more driver query,
// so the per-step paths check only in debug builds.
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/runtime/opencl_api.hpp"
#include "opencl/runtime/opencl_error.hpp"

#include <string>
#include <type_traits>
#include <vector>

namespace physarum::opencl {

// Buffers set as consecutive arguments, in this order.
using BufferList = std::vector<const DeviceBuffer*>;

namespace kernel_arguments_detail {

inline void set_one(cl::Kernel& kernel, cl_uint& index, const DeviceBuffer& buffer) {
  kernel.setArg(index++, buffer.buffer);
}
inline void set_one(cl::Kernel& kernel, cl_uint& index, const cl::Buffer& buffer) { kernel.setArg(index++, buffer); }
inline void set_one(cl::Kernel& kernel, cl_uint& index, const cl::LocalSpaceArg& local) {
  kernel.setArg(index++, local);
}
inline void set_one(cl::Kernel& kernel, cl_uint& index, const BufferList& buffers) {
  for (const DeviceBuffer* buffer : buffers) kernel.setArg(index++, buffer->buffer);
}
template <class T>
  requires(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T> && !std::is_same_v<T, bool>)
void set_one(cl::Kernel& kernel, cl_uint& index, const T& value) {
  kernel.setArg(index++, value);
}

}  // namespace kernel_arguments_detail

// Throws DeviceError when `set` differs from the kernel's parameter count.
inline void check_argument_count(const cl::Kernel& kernel, cl_uint set) {
  const cl_uint expected = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
  if (set != expected)
    throw DeviceError("kernel " + kernel.getInfo<CL_KERNEL_FUNCTION_NAME>() + " takes " + std::to_string(expected) +
                      " arguments, " + std::to_string(set) + " were set");
}

// Sets arguments 0, 1, ... of `kernel` to `arguments`; returns how many were set.
template <class... Args>
cl_uint set_arguments_unchecked(cl::Kernel& kernel, const Args&... arguments) {
  cl_uint index = 0;
  (kernel_arguments_detail::set_one(kernel, index, arguments), ...);
  return index;
}

// set_arguments_unchecked, then the count checked against the kernel's.
template <class... Args>
void set_arguments_checked(cl::Kernel& kernel, const Args&... arguments) {
  check_argument_count(kernel, set_arguments_unchecked(kernel, arguments...));
}

// What the host code calls: checked in debug builds, not in release builds (the per-step paths).
template <class... Args>
void set_arguments(cl::Kernel& kernel, const Args&... arguments) {
#ifdef NDEBUG
  set_arguments_unchecked(kernel, arguments...);
#else
  set_arguments_checked(kernel, arguments...);
#endif
}

}  // namespace physarum::opencl
