#pragma once
// Built-in procedural surfaces, used as MESH "shape:NAME" wherever a mesh file is accepted:
//   square          flat 1 m x 1 m square in z = 0, 32 x 32 cells with alternating diagonals
//   disk            flat unit disk in z = 0 built from 16 rings; its boundary is a regular 96-gon
//   disk-N          the same disk of N rings, 1 <= N <= 400 (disk-55: 9,241 vertices, the growth
//                   model's scenes)
//   sphere          icosphere of radius 1, subdivision level 4 (2562 vertices)
//   skinny-sphere   unit sphere of long thin non-Delaunay triangles (Fig. 4 of the paper): 96
//                   longitudes x 16 latitude rings, each ring twisted by two segments against the
//                   one below and every sheared quad cut along its LONG diagonal, so the angles
//                   opposite those diagonals are obtuse and the cotan weights negative
//   torus           R = 1, r = 0.4, 64 x 24 grid
//   octagonal-prism closed prism over a regular octagon (circumradius 0.5, height 1.5, centred at
//                   the origin, axis z), each side split into 2 columns x 6 rows; caps are fans
//   cube            unit cube centred at the origin, 24 x 24 squares a side, with a UV layout of
//                   3 x 2 tiles (one per side: +x, +y, -x bottom row, v up z; +z, -z, -y top row)
// All are CCW seen from outside (+z for the flat ones), in metres.
#include "common/mesh/mesh_file_reader.hpp"

#include <string>
#include <vector>

namespace physarum {

std::vector<std::string> shape_names();

// The unit disk in z = 0 as `rings` concentric rings of 6k vertices around a centre vertex
// (1 + 3 rings (rings + 1) vertices, nearly equilateral triangles): shape:disk has 16 rings; the
// growth model's benchmarks and tests take other sizes.
PolygonSoup disk_soup(int rings);
constexpr int kMaxDiskRings = 400;

// The shape's triangles as a polygon soup (load_mesh validates it like a file). NAME is without
// the "shape:" prefix. Throws InputError listing the valid names when NAME is unknown.
PolygonSoup make_shape_soup(const std::string& name);

}  // namespace physarum
