// Random byte-level corruption of small valid OBJ, OFF, PLY (ASCII and binary) and scene files,
// loaded through the real loaders (load_mesh, load_scene): each corrupted file must load or be
// refused with an InputError — no other exception, no crash — and each must finish within a time
// bound (a hang or a runaway allocation from a corrupted count shows up as a slow case). Each case
// runs in a child process, so a crash or a hang is reported as that case's failure. Seeded, so a
// failure names the format, the case and the bytes that reproduce it.
#include "common/base/errors.hpp"
#include "common/mesh/mesh_loading.hpp"
#include "common/scene/scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <random>
#include <string>
#include <csignal>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace physarum {
namespace {

using testing::TempDir;

// 400 per format in the suite (well under a second each); PHYSARUM_FUZZ_CASES=N fuzzes longer.
int cases_per_format() {
  const char* n = std::getenv("PHYSARUM_FUZZ_CASES");
  return n && std::atoi(n) > 0 ? std::atoi(n) : 400;
}
constexpr double kMaxSecondsPerCase = 2.0;

const char* const kObj = R"(# a tetrahedron with a texture coordinate and normals
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 0 1
vn 0 0 1
f 1/1 3/3 2/2
f 1/1 2/2 4/3
f 1/1 4/3 3/2
f 2/1 3/2 4/3
)";

const char* const kOff = R"(OFF
5 5 0
0 0 0
1 0 0
1 1 0
0 1 0
0.5 0.5 1
4 0 3 2 1
3 0 1 4
3 1 2 4
3 2 3 4
3 3 0 4
)";

const char* const kPlyAscii = R"(ply
format ascii 1.0
comment a tetrahedron
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
0 0 1
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
)";

std::string binary_ply() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&s](const void* p, size_t n) { s.append(static_cast<const char*>(p), n); };
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  put(v, sizeof v);
  const std::int32_t f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& face : f) {
    const unsigned char three = 3;
    put(&three, 1);
    put(face, sizeof face);
  }
  return s;
}

const char* const kScene = R"({
  "mesh": "shape:sphere",
  "scale_to_area": 4.0,
  "max_circumradius": 0.02,
  "agents": 1000,
  "time_step": 0.01,
  "sensor_distance": 0.05,
  "sensor_angle": 22.5,
  "move_rate": 0.5,
  "turn_rate": 180.0,
  "turn_frequency": 20.0,
  "deposit_rate": 1.0,
  "decay_rate": 1.0,
  "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0,
  "activation_time": 0.2,
  "integrator": "forward",
  "seed": 1,
  "steps": 10
})";

// One to four mutations: flip a bit, insert a byte (often a digit or a separator, which reach
// deeper into a parser than noise), delete a byte, or truncate.
std::string mutate(std::string s, std::mt19937& rng) {
  const std::string interesting = "0123456789-.eE \n/#{}[],:\"9";
  const int count = std::uniform_int_distribution<int>(1, 4)(rng);
  for (int m = 0; m < count && !s.empty(); ++m) {
    const size_t at = std::uniform_int_distribution<size_t>(0, s.size() - 1)(rng);
    switch (std::uniform_int_distribution<int>(0, 3)(rng)) {
      case 0: s[at] = static_cast<char>(s[at] ^ (1 << std::uniform_int_distribution<int>(0, 7)(rng))); break;
      case 1: {
        const bool noise = std::uniform_int_distribution<int>(0, 1)(rng) == 0;
        const char c = noise ? static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng))
                             : interesting[std::uniform_int_distribution<size_t>(0, interesting.size() - 1)(rng)];
        s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), c);
        break;
      }
      case 2: s.erase(at, 1); break;
      default: s.resize(at); break;
    }
  }
  return s;
}

std::string printable(const std::string& s) {
  std::string out;
  for (const unsigned char c : s) {
    if (c == '\n') out += "\\n";
    else if (c >= 32 && c < 127) out += static_cast<char>(c);
    else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      out += b;
    }
  }
  return out;
}

// How one load ended, as the child process that ran it reports it.
enum class Outcome { kLoaded, kRefused, kOtherException, kCrashed, kTimedOut };

// Runs load(path) in a child process (so that an abort, a crash or a hang in a third-party reader
// is reported as this case's failure instead of ending or stalling the suite), killed after
// kMaxSecondsPerCase. An exception other than InputError comes back as its message.
template <class Load>
Outcome load_in_child(const std::string& path, Load load, std::string& message) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    ::close(pipe_fds[0]);
    int code = 0;
    std::string what;
    try {
      load(path);
    } catch (const InputError&) {
      code = 1;
    } catch (const std::exception& e) {
      code = 2;
      what = std::string(typeid(e).name()) + ": " + e.what();
    }
    if (!what.empty() && ::write(pipe_fds[1], what.data(), what.size()) < 0) code = 3;
    ::_exit(code);
  }
  ::close(pipe_fds[1]);
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  Outcome outcome = Outcome::kTimedOut;
  while (true) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) {
      if (WIFEXITED(status) && WEXITSTATUS(status) <= 2)
        outcome = WEXITSTATUS(status) == 0 ? Outcome::kLoaded
                  : WEXITSTATUS(status) == 1 ? Outcome::kRefused
                                             : Outcome::kOtherException;
      else
        outcome = Outcome::kCrashed;
      break;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > kMaxSecondsPerCase) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      break;
    }
    ::usleep(200);
  }
  char buffer[512];
  ssize_t n;
  while ((n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0) message.append(buffer, static_cast<size_t>(n));
  ::close(pipe_fds[0]);
  if (outcome == Outcome::kCrashed)
    message = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) : "exit status " + std::to_string(WEXITSTATUS(status));
  return outcome;
}

// Loads mutations of `valid` through `load`; only success or InputError may come out, in time.
template <class Load>
void fuzz(const std::string& name, const std::string& valid, const std::string& extension, std::uint32_t seed,
          Load load) {
  TempDir dir;
  const std::string path = (dir.path / ("fuzz" + extension)).string();
  std::mt19937 rng(seed);
  int refused = 0;
  const int cases = cases_per_format();
  for (int i = 0; i < cases; ++i) {
    const std::string text = mutate(valid, rng);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    std::string message;
    switch (load_in_child(path, load, message)) {
      case Outcome::kLoaded: break;
      case Outcome::kRefused: ++refused; break;
      case Outcome::kOtherException:
        ADD_FAILURE() << name << " case " << i << ": not an InputError: " << message << "\n  input: " << printable(text);
        break;
      case Outcome::kCrashed:
        ADD_FAILURE() << name << " case " << i << ": crashed (" << message << ")\n  input: " << printable(text);
        break;
      case Outcome::kTimedOut:
        ADD_FAILURE() << name << " case " << i << ": took longer than " << kMaxSecondsPerCase
                      << " s\n  input: " << printable(text);
        break;
    }
  }
  // The mutations must reach the parser's error paths, or the test proves nothing.
  EXPECT_GT(refused, cases / 10) << name << ": too few corrupted files were refused";
}

TEST(InputFuzz, ObjLoadsOrRefuses) {
  fuzz("OBJ", kObj, ".obj", 1, [](const std::string& p) { load_mesh(p); });
}
TEST(InputFuzz, OffLoadsOrRefuses) {
  fuzz("OFF", kOff, ".off", 2, [](const std::string& p) { load_mesh(p); });
}
TEST(InputFuzz, AsciiPlyLoadsOrRefuses) {
  fuzz("PLY", kPlyAscii, ".ply", 3, [](const std::string& p) { load_mesh(p); });
}
TEST(InputFuzz, BinaryPlyLoadsOrRefuses) {
  fuzz("binary PLY", binary_ply(), ".ply", 4, [](const std::string& p) { load_mesh(p); });
}
TEST(InputFuzz, SceneLoadsOrRefuses) {
  fuzz("scene", kScene, ".json", 5, [](const std::string& p) { load_scene(p); });
}

}  // namespace
}  // namespace physarum
