#pragma once
// A time-lapse of a run (`physarum run --frames K`): K pictures evenly spaced in steps, the last one
// at the final step, drawn as the preview is (same view, same colour range, so frames compare), and
// written as an image sequence DIR/frames/frame_0001.png ... plus an animated DIR/frames.gif.
//
// Frames are kept in memory until the run's other outputs are written, so a run that fails leaves
// no partial sequence; --frames is capped so that memory stays bounded (1000 frames of 800x600 are
// 1.4 GB).
#include "common/output/preview_image.hpp"

#include <string>
#include <vector>

namespace physarum {

class TimeLapse {
 public:
  static constexpr int kMaxFrames = 1000;

  // frames = 0 turns the time-lapse off. UsageError for frames outside 0..kMaxFrames or more frames
  // than steps.
  TimeLapse(int frames, long long steps);

  bool enabled() const { return frames_ > 0; }
  // True when `step` (1-based) is the step of the next frame: frame k of K at round(k * steps / K).
  bool due(long long step) const;
  void add(RgbImage frame) { images_.push_back(std::move(frame)); }
  int captured() const { return static_cast<int>(images_.size()); }

  // Writes out/frames/frame_NNNN.png and out/frames.gif (frames_per_second). InputError naming the
  // file that could not be written.
  void write(const std::string& out, double frames_per_second = 12.0) const;

 private:
  int frames_ = 0;
  long long steps_ = 0;
  std::vector<RgbImage> images_;
};

// An animated GIF of `frames` (all the same size), looping forever, written through OpenImageIO
// (each frame is reduced to its own 256-colour palette) to a temporary name and renamed.
void write_animated_gif(const std::string& path, const std::vector<RgbImage>& frames, double frames_per_second);

}  // namespace physarum
