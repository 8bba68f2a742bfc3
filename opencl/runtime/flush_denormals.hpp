#pragma once
// Denormal numbers flushed to zero on the calling thread for the life of a scope, for the host's
// float solves of device fields (opencl/host_cholesky_solve.hpp). A pheromone field decays
// exponentially wherever no agent deposits (by 1 % a step in the default scene): after ~9,000 steps
// its float values there fall below 1.2e-38, and every operation on such a denormal value takes a
// slow microcode path on x86. Measured on the 1,089-vertex square (`BM_PheromoneStep/1/1/1000/1/64`,
// which runs long enough to get there): 0.041 ms a step with denormals, 0.020 flushed. Values that
// small are zero to any statistic or picture; the reference, in double, does not reach them
// (1e-308: ~70,000 steps). x86 (MXCSR's flush-to-zero and denormals-are-zero bits) and AArch64
// (FPCR.FZ); elsewhere a no-op.
#include <cstdint>

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace physarum::opencl {

class FlushDenormalsToZero {
 public:
#if defined(__SSE__) || defined(_M_X64)
  FlushDenormalsToZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
  ~FlushDenormalsToZero() { _mm_setcsr(saved_); }

 private:
  static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
  unsigned saved_;
#elif defined(__aarch64__)
  FlushDenormalsToZero() {
    asm volatile("mrs %0, fpcr" : "=r"(saved_));
    asm volatile("msr fpcr, %0" : : "r"(saved_ | (std::uint64_t{1} << 24)));
  }
  ~FlushDenormalsToZero() { asm volatile("msr fpcr, %0" : : "r"(saved_)); }

 private:
  std::uint64_t saved_;
#endif
 public:
  FlushDenormalsToZero(const FlushDenormalsToZero&) = delete;
  FlushDenormalsToZero& operator=(const FlushDenormalsToZero&) = delete;
};

}  // namespace physarum::opencl
