#include "opencl/runtime/queued_host_task.hpp"

#include "common/base/errors.hpp"
#include "opencl/runtime/opencl_error.hpp"

#include <exception>
#include <utility>

namespace physarum::opencl {

namespace {

// The argument block of one native-kernel run. OpenCL copies it, and in the copy replaces the
// buffer's cl_mem handle (stored in `contents`) by a host pointer to the buffer's contents.
struct NativeArguments {
  QueuedHostTask* task;
  void* contents;
};

}  // namespace

bool runs_queued_host_tasks(const DeviceInfo& device) {
  return (device.device.getInfo<CL_DEVICE_EXECUTION_CAPABILITIES>() & CL_EXEC_NATIVE_KERNEL) != 0;
}

QueuedHostTask::QueuedHostTask(const ComputeContext& compute, std::string what, Work work)
    : compute_(compute), what_(std::move(what)), work_(std::move(work)) {
  if (!runs_queued_host_tasks(compute.device))
    throw DeviceError(what_ + ": " + compute.device.device_name +
                      " runs no native kernels (CL_EXEC_NATIVE_KERNEL), so it cannot run host code in its queue");
}

QueuedHostTask::~QueuedHostTask() {
  // A run still in the queue calls this object: wait for it. A failing finish leaves nothing to wait for.
  try {
    compute_.queue.finish();
  } catch (...) {
  }
}

void QueuedHostTask::enqueue(const DeviceBuffer& buffer) {
  throw_if_failed();
  cl_mem handle = buffer.buffer();
  NativeArguments arguments{this, handle};
  const void* location = &arguments.contents;
  const cl_int status = clEnqueueNativeKernel(compute_.queue(), &QueuedHostTask::run, &arguments, sizeof(arguments), 1,
                                              &handle, &location, 0, nullptr, nullptr);
  if (status != CL_SUCCESS)
    throw device_error(what_ + ": enqueueing host work on " + compute_.device.device_name, status);
}

// On the runtime's thread: the work must not throw into OpenCL's C code, so a failure is kept for
// the caller's next enqueue.
void QueuedHostTask::run(void* arguments) {
  const NativeArguments& a = *static_cast<const NativeArguments*>(arguments);
  QueuedHostTask& task = *a.task;
  try {
    task.work_(a.contents);
  } catch (const std::exception& e) {
    const std::lock_guard lock(task.failure_mutex_);
    if (task.failure_.empty()) task.failure_ = e.what();
  } catch (...) {
    const std::lock_guard lock(task.failure_mutex_);
    if (task.failure_.empty()) task.failure_ = "an unknown exception";
  }
}

void QueuedHostTask::throw_if_failed() {
  const std::lock_guard lock(failure_mutex_);
  if (!failure_.empty()) throw DeviceError(what_ + ": the host work queued on the device failed: " + failure_);
}

}  // namespace physarum::opencl
