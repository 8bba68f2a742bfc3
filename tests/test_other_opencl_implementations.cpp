// The OpenCL backend on every OpenCL implementation this machine has besides PoCL, judged by the
// harness against the reference: the agent model (tools/scenes/default.json) and reaction-diffusion
// (tools/scenes/compare/gray_scott_square.json). `tools/setup.sh --tests` installs Mesa's rusticl
// (Debian's mesa-opencl-icd), whose llvmpipe CPU device has no 64-bit atomics (the agents deposit by
// float compare-and-swap) and compiles through SPIR-V (no clang-only builtins): the two things a
// PoCL-only kernel gets wrong. rusticl shows llvmpipe only with RUSTICL_ENABLE=llvmpipe, so the
// commands here set it. Without a second implementation the test is skipped and says so.
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace physarum::testing {
namespace {

constexpr const char* kShowEveryImplementation = "RUSTICL_ENABLE=llvmpipe ";

struct ListedDevice {
  std::string index, platform, line;
};

// `physarum devices` lines: "INDEX: PLATFORM / DEVICE (details)".
std::vector<ListedDevice> listed_devices(std::string* listing) {
  const CommandResult r = run_command(std::string(kShowEveryImplementation) + "'" + PHYSARUM_EXE + "' devices");
  *listing = r.out + r.err;
  std::vector<ListedDevice> devices;
  const std::regex line_form(R"(^(\d+): (.+?) / (.*)$)");
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, line_form)) devices.push_back({m[1], m[2], line});
  }
  return devices;
}

bool is_pocl_or_simulator(const ListedDevice& d) {
  return d.platform.find("Portable Computing Language") != std::string::npos || d.platform.find("Oclgrind") != std::string::npos;
}

void expect_equivalent_on(const ListedDevice& device, const std::string& scene) {
  TempDir dir;
  const CommandResult r = run_command(std::string(kShowEveryImplementation) + "'" + PHYSARUM_EXE + "' compare " +
                                      quoted(std::filesystem::path(PHYSARUM_SOURCE_DIR) / scene) + " --device " +
                                      device.index + " --out " + quoted(dir.path));
  SCOPED_TRACE(scene + " on " + device.line);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json verdict = nlohmann::json::parse(r.out);
  EXPECT_EQ(verdict["verdict"], "equivalent") << r.out;
  // The OpenCL arm ran on that device, not on the default one.
  EXPECT_NE(verdict["arms"][0]["device"].get<std::string>().find(device.platform), std::string::npos) << r.out;
}

TEST(OtherOpenCLImplementations, AgentsAndReactionDiffusionAreEquivalentToTheReference) {
  std::string listing;
  std::vector<ListedDevice> others;
  for (const ListedDevice& d : listed_devices(&listing))
    if (!is_pocl_or_simulator(d)) others.push_back(d);
  if (others.empty())
    GTEST_SKIP() << "no OpenCL implementation besides PoCL on this machine (Debian: apt-get install mesa-opencl-icd, "
                    "which tools/setup.sh --tests installs); `physarum devices` with RUSTICL_ENABLE=llvmpipe lists:\n"
                 << listing;
  for (const ListedDevice& d : others) {
    std::cout << "[ checking ] " << d.line << "\n";
    expect_equivalent_on(d, "tools/scenes/default.json");
    expect_equivalent_on(d, "tools/scenes/compare/gray_scott_square.json");
  }
}

}  // namespace
}  // namespace physarum::testing
