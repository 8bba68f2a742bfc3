#include "api/compare/seed_runner.hpp"

#include "common/base/errors.hpp"

#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

namespace physarum {

std::vector<std::vector<double>> run_seed_tasks(const std::vector<Arm>& arms, const std::vector<SeedTask>& tasks,
                                                int jobs, const std::function<void(int done)>& progress) {
  if (jobs < 1) throw UsageError("--jobs must be >= 1");
  // One queue for the host's workers, one per OpenCL arm (fed by kDeviceStreams threads).
  std::vector<std::vector<size_t>> queues(arms.size() + 1);
  for (size_t t = 0; t < tasks.size(); ++t) {
    const Arm& arm = arms.at(static_cast<size_t>(tasks[t].arm));
    queues[arm.backend == BackendChoice::OpenCL ? static_cast<size_t>(tasks[t].arm) + 1 : 0].push_back(t);
  }

  std::vector<std::vector<double>> results(tasks.size());
  std::vector<std::atomic<size_t>> next(queues.size());
  for (auto& n : next) n = 0;
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex mutex;  // guards error, done and the progress callback
  int done = 0;

  auto work = [&](size_t queue) {
    // An OpenCL arm's thread: a queue of its own on the arm's context.
    std::optional<opencl::ComputeContext> stream;
    while (!failed) {
      const size_t k = next[queue]++;
      if (k >= queues[queue].size()) return;
      const size_t t = queues[queue][k];
      try {
        const Arm& arm = arms[static_cast<size_t>(tasks[t].arm)];
        if (queue > 0 && !stream) {
          stream = *arm.compute;
          stream->queue = cl::CommandQueue(stream->context, stream->device.device);
        }
        results[t] = arm.run_seed(tasks[t].index, stream ? &*stream : nullptr);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done);
    }
  };

  std::vector<std::thread> threads;
  const size_t host_workers = std::min(static_cast<size_t>(jobs), queues[0].size());
  for (size_t w = 0; w < host_workers; ++w) threads.emplace_back(work, 0);
  for (size_t q = 1; q < queues.size(); ++q)
    for (size_t s = 0; s < std::min(static_cast<size_t>(kDeviceStreams), queues[q].size()); ++s)
      threads.emplace_back(work, q);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace physarum
