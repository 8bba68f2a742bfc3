#include "tools/sweep/sweep_pool.hpp"

#include "common/base/errors.hpp"

#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sys/wait.h>
#include <unistd.h>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The last `lines` lines of a file (a failed job's message is at the end of its log).
std::string tail_of(const std::string& path, int lines) {
  std::ifstream file(path);
  std::deque<std::string> last;
  std::string line;
  while (std::getline(file, line)) {
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) last.pop_front();
  }
  std::string text;
  for (const std::string& l : last) text += "    " + l + "\n";
  return text;
}

// Starts `exe args...` in `folder` with stdout and stderr into the open `log`. Between fork and exec
// only async-signal-safe calls (dup2, chdir, execv, _exit): the parent may hold OpenCL's threads.
pid_t start_job(const std::string& exe, const std::vector<std::string>& args, int log, const std::string& folder) {
  std::vector<std::string> words{exe};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw InputError(std::string("physarum sweep: cannot start a job: fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    if (::chdir(folder.c_str()) != 0) _exit(126);
    ::execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

bool uses_opencl(const std::vector<std::string>& args) {
  std::string backend = "auto";
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--device") return false;  // the user chose the device
    if (args[i] == "--backend") backend = args[i + 1];
  }
  return backend == "opencl" || backend == "auto";
}

// One line of progress: a bar with the ETA from the throughput so far.
class SweepProgress {
 public:
  SweepProgress(int total, int skipped) : total_(total), done_(skipped), skipped_(skipped), tty_(::isatty(STDERR_FILENO) == 1) {}
  void finished(const SweepJob& job, bool ok, double seconds, int failed) {
    ++done_;
    ++ran_;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const int left = total_ - done_;
    const double eta = ran_ > 0 ? elapsed / ran_ * left : 0.0;
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = total_ > 0 ? kWidth * done_ / total_ : kWidth;
      std::fprintf(stderr, "\r[%s%s] %d/%d runs (%d skipped, %d failed)  ETA %.0f s ", std::string(filled, '#').c_str(),
                   std::string(kWidth - filled, ' ').c_str(), done_, total_, skipped_, failed, eta);
      if (left == 0) std::fprintf(stderr, "\n");
    } else {
      std::fprintf(stderr, "physarum sweep: %s %s in %.1f s (%d/%d, %d failed, ETA %.0f s)\n",
                   fs::path(job.out).filename().c_str(), ok ? "done" : "FAILED", seconds, done_, total_, failed, eta);
    }
    std::fflush(stderr);
  }

 private:
  int total_, done_, skipped_, ran_ = 0;
  bool tty_;
  Clock::time_point start_ = Clock::now();
};

}  // namespace

std::string job_log_path(const std::string& folder, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "run_%04d.log", index);
  return (fs::path(folder) / "logs" / name).string();
}

int open_job_log(const std::string& folder, const SweepJob& job) {
  const std::string path = job_log_path(folder, job.index);
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path + ": cannot open the job's log: " + std::strerror(errno));
  const std::time_t now = std::time(nullptr);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&now));
  const std::string line = std::string("---- physarum sweep: job ") + std::to_string(job.index) +
                           (job.resumes() ? " resumes from its checkpoint" : " starts") + ", " + when + " ----\n";
  if (::write(fd, line.data(), line.size()) < 0) {
    ::close(fd);
    throw InputError(path + ": cannot write the job's log: " + std::strerror(errno));
  }
  return fd;
}

std::string this_executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw InputError("physarum sweep: cannot find its own executable (/proc/self/exe): " + ec.message());
  return exe.string();
}

SweepPoolReport run_sweep_jobs(const std::string& folder, const std::vector<SweepJob>& jobs, int workers,
                               const std::vector<int>& devices) {
  if (workers < 1) throw UsageError("--jobs " + std::to_string(workers) + " must be >= 1");
  const std::string exe = this_executable();
  fs::create_directories(fs::path(folder) / "logs");
  SweepPoolReport report;
  std::vector<const SweepJob*> pending;
  for (const SweepJob& job : jobs) {
    if (job.finished()) ++report.skipped;
    else pending.push_back(&job);
  }
  if (report.skipped > 0)
    std::fprintf(stderr, "physarum sweep: %d of %zu runs finished before (run.json present): skipped\n", report.skipped,
                 jobs.size());
  SweepProgress progress(static_cast<int>(jobs.size()), report.skipped);

  struct Running {
    const SweepJob* job;
    int worker;
    Clock::time_point started;
  };
  std::map<pid_t, Running> running;
  std::vector<bool> busy(static_cast<std::size_t>(workers), false);
  std::size_t next = 0;
  const auto t0 = Clock::now();
  while (next < pending.size() || !running.empty()) {
    while (next < pending.size() && static_cast<int>(running.size()) < workers) {
      int worker = 0;
      while (busy[static_cast<std::size_t>(worker)]) ++worker;
      const SweepJob& job = *pending[next++];
      std::vector<std::string> args = job.run_args();
      // A resumed run keeps its checkpoint's device (another one would be refused as another run).
      if (!devices.empty() && !job.resumes() && uses_opencl(args)) {
        args.push_back("--device");
        args.push_back(std::to_string(devices[static_cast<std::size_t>(worker) % devices.size()]));
      }
      const int log = open_job_log(folder, job);
      const pid_t pid = start_job(exe, args, log, folder);
      ::close(log);
      busy[static_cast<std::size_t>(worker)] = true;
      running[pid] = Running{&job, worker, Clock::now()};
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw InputError(std::string("physarum sweep: waiting for a job: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of ours
    const Running r = it->second;
    running.erase(it);
    busy[static_cast<std::size_t>(r.worker)] = false;
    const double seconds = std::chrono::duration<double>(Clock::now() - r.started).count();
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && r.job->finished();
    if (ok) {
      ++report.ran;
    } else {
      report.failed.push_back(r.job->index);
      const std::string how = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                              : WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                                  : "stopped";
      std::fprintf(stderr, "\nphysarum sweep: job %d (%s) failed (%s); its log %s ends:\n%s", r.job->index,
                   fs::path(r.job->out).filename().c_str(), how.c_str(), job_log_path(folder, r.job->index).c_str(),
                   tail_of(job_log_path(folder, r.job->index), 3).c_str());
    }
    progress.finished(*r.job, ok, seconds, static_cast<int>(report.failed.size()));
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return report;
}

}  // namespace physarum::cli
