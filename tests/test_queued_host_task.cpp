// Host code run in the device's queue (opencl/runtime/queued_host_task.hpp): it sees what the commands
// before it wrote and the commands after it see what it wrote, on the buffer it names (not on
// another one); enqueueing it does not wait for it; a run that throws is reported at the next enqueue. Skipped
// on a device without native kernels (GPU drivers), where the field models map their buffers instead.
#include "common/base/errors.hpp"
#include "opencl/runtime/queued_host_task.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace physarum::opencl {
namespace {

const ComputeContext& compute() {
  static const ComputeContext c = make_compute_context("");
  return c;
}

#define SKIP_WITHOUT_NATIVE_KERNELS()                                                                       \
  if (!runs_queued_host_tasks(compute().device))                                                            \
  GTEST_SKIP() << compute().device.device_name << " runs no native kernels (CL_EXEC_NATIVE_KERNEL): the "  \
                                                  "field models map their buffers there instead"

std::vector<float> read(const DeviceBuffer& b, int n) {
  std::vector<float> v(static_cast<size_t>(n));
  compute().queue.enqueueReadBuffer(b.buffer, CL_TRUE, 0, v.size() * sizeof(float), v.data());
  return v;
}

TEST(QueuedHostTask, RunsInQueueOrderOnTheNamedBufferInPlace) {
  SKIP_WITHOUT_NATIVE_KERNELS();
  constexpr int n = 1000;  // not a multiple of anything the runtime might round to
  // Two buffers, the task names the second: it must get that one's contents, not the first's.
  DeviceBuffer other = allocate_written<cl_float>(compute(), "other", n);
  DeviceBuffer b = allocate_written<cl_float>(compute(), "b", n);
  // A kernel after the task, to see the task's writes.
  const cl::Program program(compute().context,
                            "kernel void add_one(global float* x, int n) { int i = get_global_id(0); if (i < n) x[i] "
                            "+= 1.0f; }",
                            true);
  cl::Kernel add_one(program, "add_one");
  add_one.setArg(0, b.buffer);
  add_one.setArg(1, n);
  {
    QueuedHostTask task(compute(), "test task", [](void* contents) {
      float* x = static_cast<float*>(contents);
      for (int i = 0; i < n; ++i) x[i] = 2.0f * x[i] + static_cast<float>(i);  // needs the fill before the task
    });
    // Enqueued, never waited for, between the fills and the kernel: only the queue's order makes the
    // values below come out.
    compute().queue.enqueueFillBuffer(other.buffer, -3.0f, 0, other.payload_bytes);
    compute().queue.enqueueFillBuffer(b.buffer, 1.5f, 0, b.payload_bytes);
    task.enqueue(b);
    compute().queue.enqueueNDRangeKernel(add_one, cl::NullRange, cl::NDRange(1024));
  }
  const std::vector<float> ov = read(other, n), bv = read(b, n);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(ov[static_cast<size_t>(i)], -3.0f) << "the task wrote the buffer it did not name, at " << i;
    // 2 * 1.5 + i from the task, + 1 from the kernel after it: small integers, exact in float.
    ASSERT_EQ(bv[static_cast<size_t>(i)], 4.0f + static_cast<float>(i)) << "b[" << i << "]";
  }
}

TEST(QueuedHostTask, EnqueueReturnsWithoutWaitingForTheWork) {
  SKIP_WITHOUT_NATIVE_KERNELS();
  DeviceBuffer a = allocate_written<cl_float>(compute(), "a", 16);
  std::atomic<bool> ran{false};
  QueuedHostTask task(compute(), "test task", [&ran](void*) { ran = true; });
  // Hold the (in-order) queue on an event only the host completes: a task that waited for its run
  // would never return from enqueue.
  cl::UserEvent gate(compute().context);
  const std::vector<cl::Event> wait_for{gate};
  compute().queue.enqueueMarkerWithWaitList(&wait_for);
  task.enqueue(a);
  EXPECT_FALSE(ran) << "the work ran before the commands ahead of it in the queue";
  gate.setStatus(CL_COMPLETE);
  compute().queue.finish();
  EXPECT_TRUE(ran);
}

TEST(QueuedHostTask, AFailedRunIsReportedAtTheNextEnqueue) {
  SKIP_WITHOUT_NATIVE_KERNELS();
  DeviceBuffer a = allocate_written<cl_float>(compute(), "a", 16);
  int runs = 0;
  QueuedHostTask task(compute(), "test task", [&runs](void*) {
    if (++runs == 1) throw InputError("the first run fails");
  });
  task.enqueue(a);
  compute().queue.finish();
  EXPECT_EQ(runs, 1);
  try {
    task.enqueue(a);
    FAIL() << "the failed run was not reported";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("the first run fails"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test task"), std::string::npos) << e.what();
  }
  EXPECT_EQ(runs, 1) << "a run was enqueued after a failure";
}

}  // namespace
}  // namespace physarum::opencl
