#pragma once
// The report of the stand-alone probe programs (physarum_device_check, physarum_oclgrind_probe):
// every check prints one "ok"/"FAILED" line, and the program exits non-zero when any failed.
#include <cstdio>
#include <string>

namespace physarum::testing {

inline int& probe_failures() {
  static int failures = 0;
  return failures;
}

inline void check(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  if (!ok) ++probe_failures();
}

// The exit status: 0 when every check passed.
inline int probe_exit_status() { return probe_failures() == 0 ? 0 : 1; }

}  // namespace physarum::testing
