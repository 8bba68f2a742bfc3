#include "opencl/runtime/program_cache.hpp"

#include "opencl/runtime/opencl_error.hpp"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

#ifndef PHYSARUM_RANDOM123_INCLUDE_DIR
#define PHYSARUM_RANDOM123_INCLUDE_DIR "/usr/include"
#endif

namespace physarum::opencl {
namespace {

// FNV-1a, 64 bit: not cryptographic, only a cache key; collisions would need adversarial input.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
    h = (h ^ 0xff) * 0x100000001b3ull;  // separator, so ("ab","c") != ("a","bc")
  }
};

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The folder holding Random123/: where the build found it, or $PHYSARUM_RANDOM123_INCLUDE (for a
// binary moved to a machine without the headers in the same place).
std::string random123_include_dir() {
  if (const char* d = std::getenv("PHYSARUM_RANDOM123_INCLUDE"); d && *d) return d;
  return PHYSARUM_RANDOM123_INCLUDE_DIR;
}

// The Random123 headers that kernels include: part of the source for caching purposes.
const std::string& random123_text() {
  static const std::string text = [] {
    std::string t;
    const std::filesystem::path dir = std::filesystem::path(random123_include_dir()) / "Random123";
    for (const char* f : {"philox.h", "array.h", "features/compilerfeatures.h", "features/openclfeatures.h"})
      t += read_file(dir / f);
    return t;
  }();
  return text;
}

std::string build_log(const cl::Program& program, const cl::Device& device) {
  try {
    return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
  } catch (const cl::Error&) {
    return "(no build log available)";
  }
}

}  // namespace

std::string program_cache_dir() {
  if (const char* d = std::getenv("PHYSARUM_CACHE_DIR"); d && *d) return std::string(d) == "off" ? "" : d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::string(d) + "/physarum";
  if (const char* d = std::getenv("HOME"); d && *d) return std::string(d) + "/.cache/physarum";
  return "";
}

std::string base_build_options() {
  return "-cl-std=CL1.2 -I " + random123_include_dir();
}

cl::Program build_program(const cl::Context& context, const DeviceInfo& device, const std::string& label,
                          const std::string& source, const std::string& extra_options) {
  const std::string options = base_build_options() + (extra_options.empty() ? "" : " " + extra_options);
  Fnv1a key;
  for (const std::string* s : {&device.platform_name, &device.device_name, &device.device_version,
                               &device.driver_version, &options, &source, &random123_text()})
    key.add(*s);
  std::ostringstream name;
  name << std::hex << key.h << ".bin";

  const std::string dir = program_cache_dir();
  const std::filesystem::path cached = dir.empty() ? std::filesystem::path() : std::filesystem::path(dir) / name.str();

  // A cached binary that the driver refuses (a different build, a corrupt file) is not an error:
  // fall through and compile from source.
  if (!dir.empty() && std::filesystem::exists(cached)) {
    const std::string bytes = read_file(cached);
    if (!bytes.empty()) {
      try {
        cl::Program::Binaries binaries{std::vector<unsigned char>(bytes.begin(), bytes.end())};
        cl::Program program(context, {device.device}, binaries);
        program.build({device.device}, options.c_str());
        return program;
      } catch (const cl::Error&) {
      }
    }
  }

  cl::Program program(context, source);
  try {
    program.build({device.device}, options.c_str());
  } catch (const cl::Error& e) {
    throw DeviceError("building OpenCL program " + label + " for " + device.device_name + " failed: " +
                      error_name(e.err()) + "\n--- build log ---\n" + build_log(program, device.device));
  }

  if (!dir.empty()) {
    try {
      const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
      if (!binaries.empty() && !binaries.front().empty()) {
        std::filesystem::create_directories(dir);
        // Write to a private temporary name and rename, so a concurrent reader never sees half a file.
        const std::filesystem::path tmp = cached.string() + ".tmp" + std::to_string(::getpid());
        {
          std::ofstream out(tmp, std::ios::binary);
          out.write(reinterpret_cast<const char*>(binaries.front().data()),
                    static_cast<std::streamsize>(binaries.front().size()));
        }
        std::filesystem::rename(tmp, cached);
      }
    } catch (const std::exception&) {
      // The cache is an optimisation: an unwritable cache folder must not fail the run.
    }
  }
  return program;
}

}  // namespace physarum::opencl
