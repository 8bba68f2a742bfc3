#pragma once
// Image-assisted colour maps (Sec. 3.4 of the paper): the colours of an exemplar picture (a photo of
// lichen, a giraffe's coat, an octopus's skin) usually lie near one curve in colour space, from the
// background through the pigment. ISOMAP [Tenenbaum, de Silva, Langford 2000] finds that curve's 1D
// parameter and a smoothing spline turns it into a colour map:
//
//   1. pixels: all border pixels and a fixed-seed random sample of the rest (`max_pixels`), in sRGB;
//      fully transparent pixels are skipped (images over 250k pixels are first thinned to a regular
//      grid of interior pixels, to bound memory).
//   2. merge: colours are binned on a CIELAB grid (cell size 1 Delta-E, grown until at most
//      `max_colors` cells remain); each cell is one node with the mean colour and the pixel count.
//   3. graph: each node joined to its `neighbours` nearest in CIELAB; separate pieces are joined by
//      their shortest connecting edges (a minimum spanning tree over the pieces), so it is connected.
//      CIELAB because its Euclidean distance approximates perceived difference: geodesic length then
//      measures how far apart two colours *look*, so the map is roughly perceptually even, and colour
//      noise in dark regions (large in sRGB ratio, small to the eye) does not tear the curve.
//   4. geodesics: Dijkstra from every node; 5. classical MDS to one dimension: the top eigenvector
//      of the double-centred squared geodesic distances (Spectra), scaled by its eigenvalue's root.
//   6. orientation: the parameter is rescaled to [0, 1] and flipped if needed so that the background
//      colour sits in the lower half, i.e. low concentration maps to the exemplar's background. The
//      background is the node with the most pixels in the border band (2% of the shorter side, at
//      least one pixel); without border pixels, the most frequent node.
//   7. fit: per sRGB channel, a penalised least-squares cubic B-spline (P-spline, Eilers & Marx
//      1996: 24 uniform intervals, second-difference penalty) over the parameter, weighted by pixel
//      counts, so many pixels at one parameter value are averaged and gaps stay smooth; sampled at
//      `stops` regular positions and clamped to [0, 1].
// Everything is deterministic (fixed seed, sorted bins).
#include "common/color/color_map.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace physarum {

struct IsomapOptions {
  int stops = 256;          // stops of the resulting map, >= 2
  int max_pixels = 40000;   // interior pixels sampled from the image
  int max_colors = 1500;    // graph nodes at most (after merging)
  int neighbours = 10;      // k of the k-nearest-neighbour graph
  std::uint64_t seed = 1;   // of the pixel sample
};

// An exemplar's pixel colours (sRGB in [0, 1]) and which of them lie in the border band.
struct ExemplarPixels {
  std::vector<SrgbColor> colors;
  std::vector<bool> on_border;  // empty, or one flag per colour
};

struct IsomapColorMap {
  ColorMap map;
  SrgbColor background{};  // the colour taken as background (t = 0 end)
  int graph_nodes = 0;     // distinct colours after merging
};

// Reads PNG, JPEG or anything OpenImageIO reads. InputError naming `path` when it cannot be read or
// has no opaque pixel.
ExemplarPixels read_exemplar_image(const std::string& path);

// InputError (naming `source`) when the pixels hold fewer than two distinct colours.
IsomapColorMap isomap_color_map(const ExemplarPixels& pixels, const std::string& name, const std::string& source,
                               const IsomapOptions& options = {});

// read_exemplar_image + isomap_color_map; the map is named after the file's stem.
IsomapColorMap isomap_color_map_from_image(const std::string& path, const IsomapOptions& options = {});

// CIELAB (D65 white) of an sRGB colour: the space the graph is built in; exposed for tests.
std::array<double, 3> srgb_to_lab(const SrgbColor& color);

}  // namespace physarum
