#pragma once
// The sketch as a picture (DIR/sketch.png of `physarum sketch`): its ellipses filled and strokes drawn
// in black on white, the window's aspect kept, so the gallery and the user see what was measured
// beside what grew. A JSON sketch has no picture of its own; a PNG sketch is redrawn from its marks.
// A sketch painted on a UV layout (--uv) is drawn over that layout's charts, in pale grey.
#include "common/mesh/input_mesh.hpp"
#include "common/output/preview_image.hpp"
#include "common/sketch/sketch.hpp"
#include "common/sketch/surface_marks.hpp"

namespace physarum {

// `size` pixels along the window's longer side; `uv_layout`: the mesh whose UV charts lie under the
// marks, or nullptr.
RgbImage draw_sketch(const Sketch& sketch, const InputMesh* uv_layout = nullptr, int size = 512);

// Marks drawn on the surface, black on light grey, on `surface` (a mesh of the input surface, such as
// a run's fields_full.ply: fine enough to show small marks) in the preview's three-quarter view.
RgbImage draw_surface_marks(const SurfaceMarks& marks, const InputMesh& surface);

}  // namespace physarum
