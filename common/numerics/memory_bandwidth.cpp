#include "common/numerics/memory_bandwidth.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace physarum {
namespace {

constexpr std::size_t kElements = 8u << 20;  // doubles per array: 64 MB, twice the largest L3 of the test machines

}  // namespace

HostTriad::HostTriad() : a_(kElements, 0.0), b_(kElements, 1.0), c_(kElements, 2.0) {}

double HostTriad::bytes_per_second(int repeats) {
  using Clock = std::chrono::steady_clock;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  double best = 0.0;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    const Clock::time_point start = Clock::now();
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const std::size_t lo = kElements * t / threads, hi = kElements * (t + 1) / threads;
        for (std::size_t i = lo; i < hi; ++i) a_[i] = b_[i] + 3.0 * c_[i];
      });
    for (std::thread& th : pool) th.join();
    best = std::max(best, bytes_per_triad() / std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

}  // namespace physarum
