#pragma once
// Host code that the device's own command queue runs, in order with its kernels: an OpenCL native
// kernel (clEnqueueNativeKernel), offered by devices whose execution capabilities include
// CL_EXEC_NATIVE_KERNEL (PoCL's CPU device does; GPU drivers do not). The queue hands the task host
// pointers to the contents of the buffers it names, so the task works on device fields in place like
// a mapped buffer (opencl/runtime/mapped_buffer.hpp) does, but the host thread never waits for it: where a
// map blocks until every command before it has run and the unmap is one more round trip to the
// runtime's threads, enqueueing the task returns at once and the runtime runs it on its own thread
// when its turn comes (bench/README.md, "The implicit solve": those round trips were most of a
// small field's implicit step).
//
// One buffer per run: PoCL 3.1 puts the host pointers of a native kernel's several buffers into
// the wrong argument slots (given [b, a] for buffers a, b created in that order, the work saw a's
// pointer where b's belonged), so a task that needs two fields would read one as the other. With
// one buffer there is nothing to mix up. (The reaction-diffusion IMEX solve, which reads the
// right-hand sides and writes the fields, stays on mapped buffers for that reason.)
//
// The work runs on the OpenCL runtime's thread, so it must not touch what the enqueueing thread
// changes meanwhile, and it must not call OpenCL on the same queue. A task object lives as long as
// any run of it: the destructor waits for the queue.
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <functional>
#include <mutex>
#include <string>

namespace physarum::opencl {

// Whether the device runs native kernels (CL_EXEC_NATIVE_KERNEL), so QueuedHostTask can be used.
bool runs_queued_host_tasks(const DeviceInfo& device);

class QueuedHostTask {
 public:
  // The contents of the buffer enqueue() named, as a host pointer.
  using Work = std::function<void(void* contents)>;

  // `what` names the task in error messages. Throws DeviceError when the device runs no native
  // kernels (runs_queued_host_tasks).
  QueuedHostTask(const ComputeContext& compute, std::string what, Work work);
  ~QueuedHostTask();  // waits for the queue: no enqueued run may outlive the work it calls
  QueuedHostTask(const QueuedHostTask&) = delete;
  QueuedHostTask& operator=(const QueuedHostTask&) = delete;

  // Enqueues one run of the work on `buffer` and returns without waiting. The commands enqueued
  // before it have finished when it runs, and those after it see what it wrote. Throws DeviceError
  // when an earlier run failed (the work threw: the message says what), or when the queue refuses
  // the command.
  void enqueue(const DeviceBuffer& buffer);

 private:
  static void run(void* arguments);
  void throw_if_failed();

  ComputeContext compute_;
  std::string what_;
  Work work_;
  // What the work threw, if it did; written on the runtime's thread, read on the caller's.
  std::mutex failure_mutex_;
  std::string failure_;
};

}  // namespace physarum::opencl
