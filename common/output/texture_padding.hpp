#pragma once
// Seam padding of a baked texture (Blender's "bake margin"): texels outside every UV chart near a
// chart take values continued from it, so that bilinear filtering and mipmaps, which mix a chart's
// edge texels with their neighbours, do not bleed background colour into the surface along seams.
//
// Dilation, one ring per pass: a texel outside every chart that touches (8-neighbourhood) texels
// already filled takes the mean of those, read as they were before the pass (so the result does not
// depend on visiting order). After `margin` passes every texel within Chebyshev distance `margin`
// of a chart texel is filled, and none farther away; those get the background value. Chart texels
// are never changed. Distances wrap around the image edges, as UVs do (a chart touching the left
// edge is padded on the right edge: a repeating sampler reads there).
#include <cstdint>
#include <vector>

namespace physarum {

enum class TexelCoverage : std::uint8_t {
  Background = 0,  // outside every chart and beyond the margin
  Padding = 1,     // outside every chart, within the margin: a value continued from a chart
  Chart = 2,       // the centre lies in a UV triangle: a value of the surface
};

// `values` holds `channels` floats per texel, row-major; `coverage` one entry per texel, on input
// Chart or Background (anything not Chart is treated as outside). Fills the padding, sets every other
// non-chart texel to `background` (each channel) and marks the coverage.
void pad_charts(int width, int height, int channels, std::vector<float>& values, std::vector<TexelCoverage>& coverage,
                int margin, float background);

}  // namespace physarum
