#pragma once
// The largest image physarum decodes (map textures, colour-map exemplars, sketches): checked from
// the header's dimensions before a pixel is read, so a 300-byte file that claims 60,000 x 60,000
// pixels is refused at once instead of after gigabytes of allocation and decoding.
#include "common/base/errors.hpp"

#include <string>

namespace physarum {

// 8192 x 8192 pixels (a float RGBA map of that size is 1 GiB in memory).
constexpr long long kMaxImagePixels = 8192LL * 8192LL;

// InputError "WHAT: the image PATH is W x H pixels, more than the 67,108,864 (8192 x 8192) physarum
// reads" when width x height exceeds kMaxImagePixels.
inline void check_image_budget(long long width, long long height, const std::string& path, const std::string& what) {
  if (width > 0 && height > 0 && width * height > kMaxImagePixels)
    throw InputError(what + ": the image " + path + " is " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels, more than the " + std::to_string(kMaxImagePixels) +
                     " (8192 x 8192) physarum reads; scale it down");
}

}  // namespace physarum
