#include "common/output/time_lapse.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace physarum {

TimeLapse::TimeLapse(int frames, long long steps) : frames_(frames), steps_(steps) {
  if (frames < 0 || frames > kMaxFrames)
    throw UsageError("--frames " + std::to_string(frames) + " must be between 0 and " + std::to_string(kMaxFrames));
  if (frames > steps)
    throw UsageError("--frames " + std::to_string(frames) + " asks for more frames than the run's " +
                     std::to_string(steps) + " steps");
}

bool TimeLapse::due(long long step) const {
  if (captured() >= frames_) return false;
  const long long k = captured() + 1;
  // Integer rounding of k * steps / frames: exact, and the last frame lands on the last step.
  return step == (2 * k * steps_ + frames_) / (2 * frames_);
}

void TimeLapse::write(const std::string& out, double frames_per_second) const {
  if (!enabled()) return;
  const std::filesystem::path folder = std::filesystem::path(out) / "frames";
  create_output_folder(folder.string());
  for (int k = 0; k < captured(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k + 1);
    write_rgb_png((folder / name).string(), images_[k]);
  }
  write_animated_gif((std::filesystem::path(out) / "frames.gif").string(), images_, frames_per_second);
}

void write_animated_gif(const std::string& path, const std::vector<RgbImage>& frames, double frames_per_second) {
  if (frames.empty()) throw InputError(path + ": no frames to write");
  for (const RgbImage& f : frames)
    if (f.width != frames[0].width || f.height != frames[0].height)
      throw InputError(path + ": frames differ in size");
  write_file_atomically(path, [&](const std::string& temporary) {
    auto out = OIIO::ImageOutput::create("gif");
    if (!out) throw InputError(path + ": cannot write GIF: " + OIIO::geterror());
    OIIO::ImageSpec spec(frames[0].width, frames[0].height, 3, OIIO::TypeDesc::UINT8);
    // The GIF writer takes the frame rate as a rational; hundredths of a second are GIF's unit.
    const int rate[2] = {static_cast<int>(std::lround(frames_per_second * 100.0)), 100};
    spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
    spec.attribute("oiio:LoopCount", 0);  // 0 = loop forever
    const std::vector<OIIO::ImageSpec> specs(frames.size(), spec);
    if (!out->open(temporary, static_cast<int>(specs.size()), specs.data()))
      throw InputError(path + ": cannot write GIF: " + out->geterror());
    for (size_t k = 0; k < frames.size(); ++k) {
      if (k > 0 && !out->open(temporary, spec, OIIO::ImageOutput::AppendSubimage))
        throw InputError(path + ": cannot write GIF frame " + std::to_string(k + 1) + ": " + out->geterror());
      if (!out->write_image(OIIO::TypeDesc::UINT8, frames[k].pixels.data()))
        throw InputError(path + ": cannot write GIF frame " + std::to_string(k + 1) + ": " + out->geterror());
    }
    if (!out->close()) throw InputError(path + ": cannot write GIF: " + out->geterror());
  });
}

}  // namespace physarum
