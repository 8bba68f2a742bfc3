#pragma once
// Runs a sweep's jobs (tools/sweep/sweep_plan.hpp) on this machine: a pool of `workers` child processes,
// each job one `physarum run` of this very executable (/proc/self/exe) with the job's arguments, so
// a job that crashes, runs out of memory or is killed takes only itself down. Jobs whose run.json
// exists are skipped (a sweep resumes where it stopped); a failed job is reported with the tail of
// its log and the others go on. Each job's output goes to DIR/logs/run_NNNN.log, and each runs with
// DIR as its working directory (the paths of jobs.jsonl are relative to it).
//
// OpenCL jobs are spread over the devices: when the runs use the OpenCL backend (--backend opencl
// or auto) with no --device of their own and there are several devices, worker w runs its jobs
// with --device (w mod devices).
#include "tools/sweep/sweep_plan.hpp"

#include <string>
#include <vector>

namespace physarum::cli {

struct SweepPoolReport {
  int ran = 0;       // jobs started and finished successfully
  int skipped = 0;   // already finished before
  std::vector<int> failed;  // job indices
  double seconds = 0.0;     // wall time of the pool
};

// Runs `jobs` with `workers` processes in parallel (>= 1). Progress and ETA on stderr: a bar
// redrawn in place on a terminal, one line per finished job otherwise. `devices` are the OpenCL
// device indices to spread over (empty: none added).
SweepPoolReport run_sweep_jobs(const std::string& folder, const std::vector<SweepJob>& jobs, int workers,
                               const std::vector<int>& devices);

// DIR/logs/run_NNNN.log: where every way of running job `index` writes the run's output.
std::string job_log_path(const std::string& folder, int index);

// Opens job's log for appending (a resumed run's log keeps the stopped attempt's lines above), close
// on exec, and writes a line saying when and how this attempt starts. InputError naming the log when
// it cannot be opened.
int open_job_log(const std::string& folder, const SweepJob& job);

// The path of the running executable (/proc/self/exe resolved), for the jobs and the emitted scripts.
std::string this_executable();

}  // namespace physarum::cli
