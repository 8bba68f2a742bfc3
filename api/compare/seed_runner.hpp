#pragma once
// Runs the seeds of a comparison on every core and device at once: the seeds of reference arms on a
// pool of `jobs` worker threads, the seeds of each OpenCL arm on kDeviceStreams threads of their own,
// each feeding the arm's device through a command queue of its own (a small scene's kernels do not
// fill a device: two simulations in flight keep it busy while the host prepares the next
// launches), all at the same time. Every result is stored at its task's place, so what comes back
// does not depend on which thread finished first: `--jobs 1` and `--jobs 8` give the same numbers.
#include "api/compare/comparison_arms.hpp"

#include <functional>
#include <vector>

namespace physarum {

constexpr int kDeviceStreams = 2;

struct SeedTask {
  int arm = 0;
  int index = 0;  // the seed's index within its arm (Arm::seed)
};

// Runs `tasks` and returns their metrics in task order. `progress(done)` is called (serialised)
// after each finished task. The first exception a task throws is rethrown here once every thread
// has stopped (the others take no new task after it).
std::vector<std::vector<double>> run_seed_tasks(const std::vector<Arm>& arms, const std::vector<SeedTask>& tasks,
                                                int jobs, const std::function<void(int done)>& progress = {});

}  // namespace physarum
