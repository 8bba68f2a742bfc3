// Inputs built to take the machine, refused before anything is spent on them: a map definition
// nested far deeper than any scene needs (its inline maps would cost time and memory quadratic in
// the depth), an image whose 300-byte header claims 60,000 x 60,000 pixels, and a sweep whose grid
// multiplies to a hundred million jobs. Each must be refused with a message that states the limit,
// well inside the time bound the byte-level fuzz test (test_input_fuzz.cpp) uses per case.
#include "common/base/errors.hpp"
#include "common/base/image_budget.hpp"
#include "common/color/isomap_color_map.hpp"
#include "common/maps/map_image.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_fields.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <string>

namespace physarum {
namespace {

using testing::TempDir;
constexpr double kMaxSeconds = 2.0;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A scene whose one map is `depth` "invert"s around an axis ramp, as text (building it as a JSON
// value would itself be deep).
std::string nested_map_scene(int depth) {
  std::string map;
  for (int i = 0; i < depth; ++i) map += R"({"invert": )";
  map += R"({"axis": "x"})";
  map += std::string(static_cast<size_t>(depth), '}');
  return R"({"mesh": "shape:square", "agents": 10, "time_step": 0.01, "sensor_distance": 0.05,
             "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180, "turn_frequency": 20, "deposit_rate": 1,
             "decay_rate": 1, "diffuse_rate": 0.0002, "mean_lifetime": 1, "activation_time": 0.2,
             "maps": {"deep": )" + map + R"(}, "spawn_weight": "deep"})";
}

std::string load_error(const TempDir& dir, const std::string& text) {
  const std::string path = (dir.path / "scene.json").string();
  std::ofstream(path) << text;
  return testing::input_error_of([&] { load_scene(path); });
}

TEST(HostileInputs, AMapNestedDeeperThanTheLimitIsRefusedWhileParsing) {
  TempDir dir;
  for (const int depth : {100, 20000, 200000}) {
    const auto start = std::chrono::steady_clock::now();
    const std::string message = load_error(dir, nested_map_scene(depth));
    EXPECT_NE(message.find("nested deeper than 64 levels"), std::string::npos) << depth << ": " << message;
    EXPECT_LT(seconds_since(start), kMaxSeconds) << depth << " levels";
  }
  // Under the limit the nesting itself is fine: the scene loads (the limit is where it says it is).
  EXPECT_EQ(load_error(dir, nested_map_scene(kMaxSceneNesting - 4)), "");
}

TEST(HostileInputs, ASceneBuiltInCodeIsHeldToTheSameNestingLimit) {
  nlohmann::json deep = {{"axis", "x"}};
  for (int i = 0; i < 1000; ++i) deep = nlohmann::json{{"invert", std::move(deep)}};
  const nlohmann::json scene = {{"mesh", "shape:square"}, {"agents", 10}, {"time_step", 0.01}, {"maps", {{"deep", deep}}}};
  const std::string message = testing::input_error_of([&] { scene_from_json(scene); });
  EXPECT_NE(message.find("scene: nested deeper than 64 levels"), std::string::npos) << message;
}

// ---- an image header that lies about its size ----

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string big_endian(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(static_cast<std::uint32_t>(data.size())) + type + data + big_endian(crc32(type + data));
}

// A valid PNG signature and IHDR (8-bit RGB, width x height) followed by a few bytes of image data:
// the header is all a reader sees before it decides to allocate.
std::string lying_png(std::uint32_t width, std::uint32_t height) {
  const std::string ihdr = big_endian(width) + big_endian(height) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string idat("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat) + png_chunk("IEND", "");
}

TEST(HostileInputs, AnImageClaimingTooManyPixelsIsRefusedFromItsHeader) {
  TempDir dir;
  const std::string path = (dir.path / "huge.png").string();
  const std::string png = lying_png(60000, 60000);
  ASSERT_LT(png.size(), 100u);
  std::ofstream(path, std::ios::binary) << png;
  auto start = std::chrono::steady_clock::now();
  std::string message = testing::input_error_of([&] { read_map_image(path, TextureChannel::Red, "maps.photo"); });
  EXPECT_NE(message.find("60000 x 60000 pixels"), std::string::npos) << message;
  EXPECT_NE(message.find("8192 x 8192"), std::string::npos) << "the message states the budget: " << message;
  EXPECT_LT(seconds_since(start), kMaxSeconds);
  start = std::chrono::steady_clock::now();
  message = testing::input_error_of([&] { read_exemplar_image(path); });
  EXPECT_NE(message.find("60000 x 60000 pixels"), std::string::npos) << message;
  EXPECT_LT(seconds_since(start), kMaxSeconds);
}

TEST(HostileInputs, TheImageBudgetIsTheStatedOne) {
  EXPECT_NO_THROW(check_image_budget(8192, 8192, "a.png", "test"));
  EXPECT_THROW(check_image_budget(8193, 8192, "a.png", "test"), InputError);
  EXPECT_THROW(check_image_budget(60000, 60000, "a.png", "test"), InputError);
}

// ---- a sweep grid past any machine ----

std::string values(int count) {
  std::string list;
  for (int i = 1; i <= count; ++i) {
    if (i > 1) list += ',';  // appended piece by piece: GCC 12 warns (-Wrestrict) on "," + std::string
    list += std::to_string(i);
  }
  return list;
}

TEST(HostileInputs, ASweepOfAHundredMillionJobsIsRefusedBeforeItIsExpanded) {
  TempDir dir;
  const auto start = std::chrono::steady_clock::now();
  const testing::CommandResult r =
      testing::run_physarum("sweep " + testing::quoted(std::string(PHYSARUM_SOURCE_DIR) + "/tools/scenes/default.json") +
                            " --vary agents=" + values(99) + " --vary turn_rate=" + values(999) + " --vary seed=" +
                            values(1000) + " --out " + testing::quoted(dir.path / "sweep"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("a sweep of 98901000 jobs"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("100000"), std::string::npos) << "the message states the limit: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "sweep")) << "nothing is written for a refused sweep";
  EXPECT_LT(seconds_since(start), kMaxSeconds);
}

}  // namespace
}  // namespace physarum
