// The OpenCL plumbing every backend kernel relies on: device choice, embedded sources, program
// build and cache, the device's Philox against the host's known answers, the deposits' rounding, and
// the device's memory-bandwidth triad.
#include "common/numerics/memory_bandwidth.hpp"
#include "common/base/philox.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/runtime/device_tuning.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/kernel_sources.hpp"
#include "opencl/runtime/memory_bandwidth.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <numeric>

namespace physarum::opencl {
namespace {

TEST(OpenCLDevices, AtLeastOneDeviceIsListed) {
  const auto devices = list_devices();
  ASSERT_FALSE(devices.empty()) << "setup installs PoCL, so an OpenCL device must exist";
  for (size_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].index, static_cast<int>(i));
    EXPECT_FALSE(devices[i].device_name.empty());
    EXPECT_GT(devices[i].max_work_group_size, 0u);
  }
}

TEST(OpenCLDevices, SelectionByIndexAndSubstring) {
  const auto devices = list_devices();
  ASSERT_FALSE(devices.empty());
  EXPECT_EQ(select_device("0").device_name, devices[0].device_name);
  // A case-insensitive piece of the platform name picks that platform's first device.
  std::string piece = devices[0].platform_name.substr(0, 4);
  for (char& ch : piece) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  EXPECT_EQ(select_device(piece).platform_name, devices[0].platform_name);
}

TEST(OpenCLDevices, NoMatchListsWhatWasFound) {
  try {
    select_device("no-such-device-xyz");
    FAIL() << "expected DeviceError";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no-such-device-xyz"), std::string::npos) << m;
    EXPECT_NE(m.find("devices found"), std::string::npos) << m;
    EXPECT_NE(m.find(list_devices()[0].device_name), std::string::npos) << m;
  }
  EXPECT_THROW(select_device("999"), DeviceError);
}

TEST(OpenCLDevices, CommandLineListsDevicesAndRejectsUnknownOnes) {
  const auto r = testing::run_physarum("devices");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0: "), std::string::npos) << r.out;
}

TEST(OpenCLKernelSources, QuotedIncludesAreInlinedOnce) {
  // Every embedded file must assemble without a missing include.
  for (const EmbeddedFile& f : embedded_kernel_files()) EXPECT_NO_THROW(kernel_source(f.name)) << f.name;
  EXPECT_THROW(kernel_source("does_not_exist.cl"), DeviceError);
}

TEST(OpenCLProgramCache, BuildFailureCarriesTheLog) {
  const ComputeContext c = make_compute_context("");
  try {
    build_program(c.context, c.device, "broken.cl", "__kernel void k(__global float* x) { x[0] = undefined_name; }");
    FAIL() << "expected DeviceError";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("broken.cl"), std::string::npos) << m;
    EXPECT_NE(m.find("undefined_name"), std::string::npos) << "the build log should name the bad identifier: " << m;
  }
}

TEST(OpenCLProgramCache, SecondBuildComesFromTheCache) {
  testing::TempDir dir;
  ::setenv("PHYSARUM_CACHE_DIR", dir.path.c_str(), 1);
  const ComputeContext c = make_compute_context("");
  const std::string src = "__kernel void twice(__global float* x) { x[get_global_id(0)] *= 2.0f; }";
  build_program(c.context, c.device, "twice.cl", src);
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 1u) << "one binary cached";
  // The cached binary must still produce a working program.
  cl::Program p = build_program(c.context, c.device, "twice.cl", src);
  cl::Buffer buf(c.context, CL_MEM_READ_WRITE, 4 * sizeof(float));
  std::vector<float> v{1, 2, 3, 4};
  c.queue.enqueueWriteBuffer(buf, CL_TRUE, 0, 4 * sizeof(float), v.data());
  cl::Kernel k(p, "twice");
  set_arguments_checked(k, buf);
  c.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(4));
  c.queue.enqueueReadBuffer(buf, CL_TRUE, 0, 4 * sizeof(float), v.data());
  EXPECT_EQ(v, (std::vector<float>{2, 4, 6, 8}));
  // A different option set is a different key.
  build_program(c.context, c.device, "twice.cl", src, "-DSOMETHING=1");
  files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 2u);
  ::unsetenv("PHYSARUM_CACHE_DIR");
}

// set_arguments sets a kernel's arguments in order, a BufferList as consecutive buffers; the checked
// form refuses a count that differs from the kernel's parameter count, naming the kernel.
TEST(OpenCLKernelArguments, AllArgumentsInOneCallAndTheCountIsChecked) {
  const ComputeContext c = make_compute_context("");
  const char* source = "__kernel void add_scaled(__global const float* a, __global const float* b, const float s,\n"
                       "                         __global float* out, __local float* unused) {\n"
                       "  const size_t i = get_global_id(0);\n"
                       "  out[i] = a[i] + s * b[i];\n"
                       "}\n";
  cl::Program p = build_program(c.context, c.device, "add_scaled.cl", source);
  const DeviceBuffer a = upload_buffer(c, "a", std::vector<float>{1, 2, 3, 4}, CL_MEM_READ_ONLY, false);
  const DeviceBuffer b = upload_buffer(c, "b", std::vector<float>{10, 20, 30, 40}, CL_MEM_READ_ONLY, false);
  const DeviceBuffer out = allocate_buffer(c, "out", 4 * sizeof(float), CL_MEM_WRITE_ONLY, true);
  cl::Kernel k(p, "add_scaled");
  set_arguments_checked(k, BufferList{&a, &b}, 0.5f, out, cl::Local(4 * sizeof(float)));
  c.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(4));
  std::vector<float> v(4);
  c.queue.enqueueReadBuffer(out.buffer, CL_TRUE, 0, 4 * sizeof(float), v.data());
  EXPECT_EQ(v, (std::vector<float>{6, 12, 18, 24}));
  EXPECT_TRUE(canary_intact(c, out));
  try {
    set_arguments_checked(k, a, b, 0.5f, out);
    FAIL() << "a missing argument passed";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("add_scaled takes 5 arguments, 4 were set"), std::string::npos) << e.what();
  }
}

// Random-access buffers (face records) live in huge pages on CPU devices (device_buffer.hpp): a
// kernel reads back exactly what was uploaded, for a payload below one huge page (the ordinary
// buffer) and one of 3 MiB plus a bit (the huge-page buffer, partly filling its last page).
TEST(OpenCLBuffers, RandomAccessUploadIsWhatKernelsRead) {
  const ComputeContext c = make_compute_context("");
  const char* source = "__kernel void copy_words(__global const uint* in, __global uint* out) {\n"
                       "  out[get_global_id(0)] = in[get_global_id(0)];\n"
                       "}\n";
  cl::Program p = build_program(c.context, c.device, "copy_words.cl", source);
  for (std::size_t words : {std::size_t{1000}, (std::size_t{3} << 18) + 17}) {
    std::vector<cl_uint> values(words);
    std::iota(values.begin(), values.end(), 0x9e3779b9u);
    const DeviceBuffer in = upload_random_access_buffer(c, "test words", values);
    const DeviceBuffer out = allocate_buffer(c, "copied words", words * sizeof(cl_uint), CL_MEM_WRITE_ONLY, true);
    cl::Kernel k(p, "copy_words");
    set_arguments_checked(k, in, out);
    c.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(words));
    std::vector<cl_uint> copied(words);
    c.queue.enqueueReadBuffer(out.buffer, CL_TRUE, 0, words * sizeof(cl_uint), copied.data());
    EXPECT_EQ(copied, values) << words << " words";
    EXPECT_TRUE(canary_intact(c, out));
  }
}

// Random123's published known-answer vectors for philox4x32-10 (kat_vectors in its distribution),
// computed on the device with the same header the host compiles.
TEST(OpenCLPhilox, KnownAnswersInsideAKernel) {
  const std::vector<cl_uint4> counters = {{{0, 0, 0, 0}},
                                          {{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}},
                                          {{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}}};
  const std::vector<cl_uint2> keys = {{{0, 0}}, {{0xffffffffu, 0xffffffffu}}, {{0xa4093822u, 0x299f31d0u}}};
  const std::vector<std::array<cl_uint, 4>> expected = {{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u},
                                                        {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu},
                                                        {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}};
  const ComputeContext c = make_compute_context("");
  cl::Program p = build_program(c.context, c.device, "philox_check.cl", kernel_source("philox_check.cl"));
  const cl_uint n = static_cast<cl_uint>(counters.size());
  cl::Buffer bc(c.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(cl_uint4), const_cast<cl_uint4*>(counters.data()));
  cl::Buffer bk(c.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(cl_uint2), const_cast<cl_uint2*>(keys.data()));
  // One canary element after the outputs catches a kernel that writes past its range.
  cl::Buffer br(c.context, CL_MEM_READ_WRITE, (n + 1) * sizeof(cl_uint4));
  std::vector<cl_uint4> results(n + 1);
  results[n] = {{0xdeadbeefu, 0xdeadbeefu, 0xdeadbeefu, 0xdeadbeefu}};
  c.queue.enqueueWriteBuffer(br, CL_TRUE, 0, (n + 1) * sizeof(cl_uint4), results.data());
  cl::Kernel k(p, "philox_known_answers");
  set_arguments_checked(k, bc, bk, br, n);
  c.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  c.queue.enqueueReadBuffer(br, CL_TRUE, 0, (n + 1) * sizeof(cl_uint4), results.data());
  for (cl_uint i = 0; i < n; ++i) {
    const auto host = philox4x32_10({counters[i].s[0], counters[i].s[1], counters[i].s[2], counters[i].s[3]},
                                    {keys[i].s[0], keys[i].s[1]});
    for (int w = 0; w < 4; ++w) {
      EXPECT_EQ(results[i].s[w], expected[i][w]) << "device, vector " << i << " word " << w;
      EXPECT_EQ(host[w], expected[i][w]) << "host, vector " << i << " word " << w;
    }
  }
  for (int w = 0; w < 4; ++w) EXPECT_EQ(results[n].s[w], 0xdeadbeefu) << "canary overwritten";
}

// Deposits round to fixed-point units with deposition.cl's nearest_integer, a cheaper form of
// convert_long_rte: it must be round-to-nearest with ties to even for every float, which the host's
// std::nearbyint (default rounding mode) gives independently. Ties at each parity, both signs, the
// edges of the range where the trick applies (2^22, 2^23) and numbers far beyond it, then a spread
// of random magnitudes.
TEST(OpenCLDeposition, FixedPointRoundingIsNearestTiesToEven) {
  std::vector<float> x = {0.0f,        -0.0f,       0.5f,          1.5f,         2.5f,        -0.5f,
                          -1.5f,       -2.5f,       0.49999997f,   1e-30f,       3.0f,        4194304.5f,
                          4194305.5f,  8388607.5f,  -8388607.5f,   8388608.0f,   8388609.0f,  16777215.0f,
                          1e12f,       -1e12f,      0x1.fffffep61f, 123456.789f, -98765.4321f};
  std::uint32_t state = 12345u;
  for (int i = 0; i < 4000; ++i) {
    state = state * 1664525u + 1013904223u;
    const float mantissa = static_cast<float>(state >> 8) * 0x1p-24f;
    x.push_back((i % 2 ? -1.0f : 1.0f) * std::ldexp(mantissa, i % 40 - 8));
  }
  const ComputeContext c = make_compute_context("");
  const std::string source = kernel_source("deposition.cl") +
                             "__kernel void round_units(__global const float* x, __global long* out) {\n"
                             "  out[get_global_id(0)] = convert_long(nearest_integer(x[get_global_id(0)]));\n"
                             "}\n";
  cl::Program p = build_program(c.context, c.device, "round_units.cl", source);
  cl::Buffer bx(c.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, x.size() * sizeof(float), x.data());
  cl::Buffer bout(c.context, CL_MEM_WRITE_ONLY, x.size() * sizeof(cl_long));
  cl::Kernel k(p, "round_units");
  set_arguments_checked(k, bx, bout);
  c.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(x.size()));
  std::vector<cl_long> rounded(x.size());
  c.queue.enqueueReadBuffer(bout, CL_TRUE, 0, x.size() * sizeof(cl_long), rounded.data());
  for (std::size_t i = 0; i < x.size(); ++i)
    ASSERT_EQ(rounded[i], static_cast<cl_long>(std::nearbyint(x[i]))) << "x = " << std::hexfloat << x[i];
}

// The device triad sizes its arrays past the device's cache, computes what it claims, and on a CPU
// device (host memory, as here) measures the same memory the host's triad does: within a factor of
// three of it, whatever the other tenants of the machine are doing to both.
// The triad's arrays are 4x the device's reported cache each where the device allows it. Devices of
// our kind differ: PoCL on some Xeons reports a cache of hundreds of MiB beside a largest allocation
// of 2 GiB and a memory a sixth of which is less than 4x that cache, and then each array is as large
// as the device allows (DeviceTriad: its largest allocation, a sixth of its memory). The rates are
// compared with the host's only when the three arrays together still stream past the cache (twice
// its size); the test says what it measured either way.
TEST(OpenCLMemoryBandwidth, DeviceTriadRunsOutsideTheCacheAndAgreesWithTheHosts) {
  const ComputeContext compute = make_compute_context("");
  const DeviceInfo& d = compute.device;
  DeviceTriad device(compute);
  const double per_array = device.bytes_per_triad() / 3.0, cache = static_cast<double>(d.global_cache_bytes);
  const double allowed = static_cast<double>(std::min<std::uint64_t>(d.max_allocation_bytes, d.global_memory_bytes / 6));
  std::cout << "triad: " << per_array / (1 << 20) << " MiB per array; cache " << cache / (1 << 20) << " MiB, allowed "
            << allowed / (1 << 20) << " MiB per array\n";
  EXPECT_TRUE(per_array >= 4.0 * cache || per_array >= allowed - 16.0)
      << "the triad is smaller than both 4x the cache and what the device allows";
  const double device_rate = device.bytes_per_second(3);
  EXPECT_TRUE(device.result_is_correct());
  if (!tuning_for(d).host_triad) GTEST_SKIP() << "the device's memory is not the host's";
  if (3.0 * per_array < 2.0 * cache)
    GTEST_SKIP() << "the largest triad the device allows (" << 3.0 * per_array / (1 << 20) << " MiB) is not twice its cache ("
                 << cache / (1 << 20) << " MiB): a rate from the cache says nothing of the host's memory";
  HostTriad host;
  const double host_rate = host.bytes_per_second(3);
  std::cout << "triad: device " << device_rate / 1e9 << " GB/s, host " << host_rate / 1e9 << " GB/s\n";
  EXPECT_GT(device_rate, host_rate / 3.0);
  EXPECT_LT(device_rate, host_rate * 3.0);
}

}  // namespace
}  // namespace physarum::opencl
