#pragma once
// A range of a device buffer seen from the host for the length of a scope: mapped on construction,
// unmapped on destruction. This is how host code works on a device field in place, with no staging
// copy of its own: where the device is the host's CPU (PoCL) the buffer already lives in host memory
// and the map hands out its address, where a read and a write each copy the range (BM_FieldRoundTrip,
// bench/README.md "The implicit solve": 0.44 against 1.5 ms for a million floats); on a GPU the
// driver copies the range over and back, which is what reads and writes would cost anyway.
//
// The map is blocking, so it also waits for every command before it in the (in-order) queue; the
// unmap is only enqueued, and the commands after it in the queue see what the host wrote. Map
// several buffers with wait = false for all but the last: one wait covers them all.
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"

#include <cstddef>

namespace physarum::opencl {

template <class T>
class MappedBuffer {
 public:
  // `count` elements of T from element `first`; flags: CL_MAP_READ, CL_MAP_WRITE or both.
  // cl::Error from the driver when the map fails (the caller turns it into a DeviceError).
  MappedBuffer(const ComputeContext& compute, const DeviceBuffer& buffer, cl_map_flags flags, std::size_t first,
               std::size_t count, bool wait = true)
      : queue_(compute.queue), buffer_(buffer.buffer), count_(count) {
    data_ = static_cast<T*>(
        queue_.enqueueMapBuffer(buffer_, wait ? CL_TRUE : CL_FALSE, flags, first * sizeof(T), count * sizeof(T)));
  }
  ~MappedBuffer() {
    // A failed unmap leaves nothing to undo here; the queue's next command reports the device's state.
    try {
      queue_.enqueueUnmapMemObject(buffer_, data_);
    } catch (...) {
    }
  }
  MappedBuffer(const MappedBuffer&) = delete;
  MappedBuffer& operator=(const MappedBuffer&) = delete;

  T* data() const { return data_; }
  std::size_t size() const { return count_; }
  T& operator[](std::size_t i) const { return data_[i]; }

 private:
  cl::CommandQueue queue_;
  cl::Buffer buffer_;
  std::size_t count_ = 0;
  T* data_ = nullptr;
};

}  // namespace physarum::opencl
