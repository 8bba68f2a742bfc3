#pragma once
// A picture of one surface map (`physarum map`'s FILE.png), to see what a simulation would read
// before running it. Drawn with the preview renderer (common/output/preview_image.hpp: the same
// three-quarter view, shading and fit), with a band underneath that names the map and its range:
//   a scalar map  coloured through viridis from its minimum (left end of the strip under the
//                 picture) to its maximum (right end), both printed; a constant map is one colour;
//   a vector map  drawn as short arrows lying on a neutral grey surface, one per cell of a 3D grid
//                 of about 30 cells across the bounding box (so the density does not depend on the
//                 mesh's resolution), at the centroid of the face nearest the cell's centre, pointing
//                 along the face's vector, as long as the cell times |v| / max |v|; faces with a zero
//                 vector get none. The arrows are thin triangles just above (and below) the face, so
//                 the renderer's depth test hides those on the far side.
// Text needs the DejaVu Sans font (fonts-dejavu-core); without it the band is drawn unlabelled.
#include "common/base/element_data.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/output/preview_image.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace physarum {

struct MapPreviewOptions {
  int width = 800;   // the whole picture, band included
  int height = 600;  // the band takes kMapPreviewBand rows of it when height >= 2 * kMapPreviewBand
  double azimuth_deg = 35.0;
  double elevation_deg = 25.0;
};

constexpr int kMapPreviewBand = 56;

// `mesh` coloured by `values` (one per vertex of `mesh`: the full-resolution mesh shows every
// intrinsic vertex's value). InputError on a size mismatch or a picture size outside 1..16384.
RgbImage render_scalar_map_preview(const InputMesh& mesh, const InputVertexData<double>& values, const std::string& name,
                                   const MapPreviewOptions& options = {});

// `input` with one vector per triangle (input coordinates, in the face's plane), drawn as arrows.
// InputError on a size mismatch or a picture size outside 1..16384.
RgbImage render_vector_map_preview(const InputMesh& input, const std::vector<Eigen::Vector3d>& vectors,
                                   const std::string& name, const MapPreviewOptions& options = {});

}  // namespace physarum
