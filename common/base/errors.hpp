#pragma once
// The two kinds of failure the command line distinguishes: bad input data or values
// (exit 1) and bad command-line usage (exit 2). Messages say what is wrong and where.
#include <stdexcept>
#include <string>

namespace physarum {

// A file, mesh or scene value that cannot be used; the message names the file and the first
// offending element. The command line maps it to exit code 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A malformed command line (unknown flag, conflicting options). Exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The compute device failed us: no OpenCL platform or device, a kernel that does not build (the
// message carries the build log), an OpenCL call that returned an error (named), out of device
// resources. Exit code 1.
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace physarum
