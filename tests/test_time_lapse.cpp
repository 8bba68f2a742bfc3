// Time-lapse (`physarum run --frames K`): frames fall on evenly spaced steps with the last on the
// final step; the sequence and the animated GIF hold K pictures; the last frame is the preview
// (same state, same view, same colours); impossible requests are usage errors.
#include "common/base/errors.hpp"
#include "common/output/time_lapse.hpp"
#include "test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace physarum {
namespace {

namespace fs = std::filesystem;

std::vector<long long> due_steps(int frames, long long steps) {
  TimeLapse lapse(frames, steps);
  std::vector<long long> due;
  for (long long s = 1; s <= steps; ++s)
    if (lapse.due(s)) {
      due.push_back(s);
      lapse.add(RgbImage{});
    }
  return due;
}

TEST(TimeLapse, FramesAreEvenlySpacedAndEndOnTheLastStep) {
  // k * steps / K rounded: 10/3 -> 3, 20/3 -> 7, 30/3 -> 10.
  EXPECT_EQ(due_steps(3, 10), (std::vector<long long>{3, 7, 10}));
  EXPECT_EQ(due_steps(4, 100), (std::vector<long long>{25, 50, 75, 100}));
  EXPECT_EQ(due_steps(5, 5), (std::vector<long long>{1, 2, 3, 4, 5}));
  EXPECT_EQ(due_steps(1, 7), (std::vector<long long>{7}));
  EXPECT_TRUE(due_steps(0, 7).empty());
  EXPECT_THROW(TimeLapse(8, 7), UsageError);
  EXPECT_THROW(TimeLapse(-1, 7), UsageError);
  EXPECT_THROW(TimeLapse(TimeLapse::kMaxFrames + 1, 1'000'000), UsageError);
}

RgbImage read_png(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  EXPECT_TRUE(in) << p;
  if (!in) return {};
  RgbImage image{in->spec().width, in->spec().height, {}};
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * 3);
  EXPECT_EQ(in->spec().nchannels, 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, image.pixels.data());
  return image;
}

TEST(TimeLapse, RunWritesTheSequenceAndAnAnimatedGif) {
  testing::TempDir dir;
  std::ofstream(dir.path / "scene.json") << R"({
  "mesh": "shape:square", "scale_to_area": 1.0, "agents": 1000, "time_step": 0.02,
  "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5, "turn_rate": 180.0,
  "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0, "diffuse_rate": 0.0002,
  "mean_lifetime": 1.0, "activation_time": 0.2, "integrator": "forward", "seed": 3
})";
  const std::string scene = "'" + (dir.path / "scene.json").string() + "'";
  const fs::path out = dir.path / "run";
  const auto r = testing::run_physarum("run " + scene + " --backend reference --steps 30 --frames 3 --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  std::vector<RgbImage> frames;
  for (int k = 1; k <= 3; ++k) frames.push_back(read_png(out / "frames" / ("frame_000" + std::to_string(k) + ".png")));
  EXPECT_FALSE(fs::exists(out / "frames" / "frame_0004.png"));
  // The last frame shows the final state exactly as preview.png does.
  EXPECT_EQ(frames[2].pixels, read_png(out / "preview.png").pixels);
  EXPECT_NE(frames[0].pixels, frames[2].pixels);  // the pattern changed between step 10 and 30

  auto gif = OIIO::ImageInput::open((out / "frames.gif").string());
  ASSERT_TRUE(gif) << OIIO::geterror();
  int subimages = 0;
  while (gif->seek_subimage(subimages, 0)) {
    EXPECT_EQ(gif->spec().width, frames[0].width);
    EXPECT_EQ(gif->spec().height, frames[0].height);
    ++subimages;
  }
  EXPECT_EQ(subimages, 3);

  // More frames than steps: a usage error, and nothing written.
  const fs::path none = dir.path / "none";
  EXPECT_EQ(testing::run_physarum("run " + scene + " --steps 30 --frames 31 --out '" + none.string() + "'").exit_code, 2);
  EXPECT_FALSE(fs::exists(none));
}

}  // namespace
}  // namespace physarum
