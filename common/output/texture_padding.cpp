#include "common/output/texture_padding.hpp"

#include "common/base/errors.hpp"

#include <algorithm>
#include <array>
#include <string>

namespace physarum {

void pad_charts(int width, int height, int channels, std::vector<float>& values, std::vector<TexelCoverage>& coverage,
                int margin, float background) {
  const size_t texels = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (width < 1 || height < 1 || channels < 1 || coverage.size() != texels ||
      values.size() != texels * static_cast<size_t>(channels) || margin < 0)
    throw InputError("texture padding: inconsistent image (" + std::to_string(width) + "x" + std::to_string(height) +
                     ", " + std::to_string(channels) + " channels, margin " + std::to_string(margin) + ")");
  const auto ch = static_cast<size_t>(channels);
  std::vector<std::uint8_t> filled(texels), queued(texels, 0);
  for (size_t t = 0; t < texels; ++t) filled[t] = coverage[t] == TexelCoverage::Chart;

  // Calls visit(neighbour index) for the 8 neighbours of (x, y), wrapping around the edges. On an
  // image narrower or lower than 3 texels the wrap reaches some texel twice (or the texel itself):
  // each distinct neighbour is visited once.
  const bool tiny = width < 3 || height < 3;
  auto for_each_neighbour = [&](int x, int y, auto&& visit) {
    const size_t self = static_cast<size_t>(y) * width + x;
    std::array<size_t, 8> seen{};
    int seen_count = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const size_t n = static_cast<size_t>((y + dy + height) % height) * width + (x + dx + width) % width;
        if (n == self) continue;
        if (tiny) {
          if (std::find(seen.begin(), seen.begin() + seen_count, n) != seen.begin() + seen_count) continue;
          seen[static_cast<size_t>(seen_count++)] = n;
        }
        visit(n);
      }
  };

  // The first ring: texels outside every chart with a chart neighbour.
  std::vector<size_t> ring;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t t = static_cast<size_t>(y) * width + x;
      if (filled[t]) continue;
      bool touches = false;
      for_each_neighbour(x, y, [&](size_t n) { touches = touches || filled[n]; });
      if (touches) {
        ring.push_back(t);
        queued[t] = 1;
      }
    }

  std::vector<float> ring_values;
  std::vector<float> sum(ch);
  for (int pass = 0; pass < margin && !ring.empty(); ++pass) {
    ring_values.assign(ring.size() * ch, 0.0f);
    for (size_t r = 0; r < ring.size(); ++r) {
      const int x = static_cast<int>(ring[r] % width), y = static_cast<int>(ring[r] / width);
      std::fill(sum.begin(), sum.end(), 0.0f);
      int count = 0;
      for_each_neighbour(x, y, [&](size_t n) {
        if (!filled[n]) return;
        ++count;
        for (size_t c = 0; c < ch; ++c) sum[c] += values[n * ch + c];
      });
      for (size_t c = 0; c < ch; ++c) ring_values[r * ch + c] = sum[c] / static_cast<float>(count);
    }
    std::vector<size_t> next;
    for (size_t r = 0; r < ring.size(); ++r) {
      const size_t t = ring[r];
      filled[t] = 1;
      coverage[t] = TexelCoverage::Padding;
      for (size_t c = 0; c < ch; ++c) values[t * ch + c] = ring_values[r * ch + c];
    }
    for (const size_t t : ring)
      for_each_neighbour(static_cast<int>(t % width), static_cast<int>(t / width), [&](size_t n) {
        if (filled[n] || queued[n]) return;
        queued[n] = 1;
        next.push_back(n);
      });
    ring = std::move(next);
  }

  for (size_t t = 0; t < texels; ++t)
    if (!filled[t]) {
      coverage[t] = TexelCoverage::Background;
      for (size_t c = 0; c < ch; ++c) values[t * ch + c] = background;
    }
}

}  // namespace physarum
