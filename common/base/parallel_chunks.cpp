#include "common/base/parallel_chunks.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace physarum {

int parallel_worker_count() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

void parallel_chunks(int chunks, const std::function<void(int)>& work) {
  if (chunks <= 0) return;
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (int c = next++; c < chunks && !failed; c = next++) {
      try {
        work(c);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };
  const int helpers = std::min(parallel_worker_count(), chunks) - 1;
  std::vector<std::thread> threads;
  threads.reserve(static_cast<size_t>(helpers));
  for (int t = 0; t < helpers; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace physarum
