#pragma once
// The growing sheet (common/growth/sheet_refinement.hpp: GrowingSheet) as a surface the
// reaction–diffusion backends run on, and its maps, at any moment of a growth run.
//
// The surface is the sheet's own triangulation on its REST metric, not on its current shape: the
// cotan Laplacian and the lumped masses come from rest edge lengths, so the pattern depends on the
// tissue (how much each piece grew) and neither on how the shell happens to bend nor on how the
// triangles were cut. An edge's rest length is the root of the mean of what its two faces' rest
// metrics say (they differ where neighbouring faces grew differently: the incompatibility that
// makes the sheet buckle). The sheet is not flipped to Delaunay: its vertices and faces are the
// shell's, one for one, so values pass between the shell and the backends without interpolation.
//
// Maps ride on the sheet: scalar maps as per-vertex values (averaged onto new vertices like the
// concentrations), vector maps as per-face directions written on the faces' rest edge vectors
// (carried exactly onto the children of a split face), so a map means the same tissue as the sheet
// grows and is refined.
#include "common/growth/sheet_refinement.hpp"
#include "common/maps/map_evaluation.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/prepared_surface.hpp"

#include <string>
#include <vector>

namespace physarum {

// The sheet's current shape as a mesh (positions and faces; no UVs). `source` names it in messages.
InputMesh sheet_mesh(const GrowingSheet& sheet, const std::string& source);

// The surface described above: input = simulated = sheet_mesh, the domain on the rest metric, every
// input vertex its own intrinsic vertex. InputError when a face's averaged rest lengths no longer
// form a triangle (growth far too uneven for one step).
PreparedSurface sheet_surface(const GrowingSheet& sheet, const std::string& source);

// A sheet at rest in the shape of `mesh`, with its initial areas recorded and nothing carried yet.
// InputError for a mesh the shell cannot take (common/shell/shell_topology.hpp).
GrowingSheet sheet_at_rest(const InputMesh& mesh);

// A growth scene's starting sheet: its mesh loaded and scaled as the scene says, at rest in its
// initial shape. InputError for refinement keys (max_circumradius, min_angle: the growth model
// refines with "refine") and for a mesh the shell cannot take (common/shell/shell_topology.hpp).
GrowingSheet initial_sheet(const Scene& scene);

// The maps the sheet carries: which scalar maps sit in sheet.values from index `first_value` on,
// and which vector maps in sheet.directions, in order.
struct SheetMapLayout {
  int first_value = 0;
  std::vector<std::string> scalar;
  std::vector<std::string> vector;
};

// Appends `maps` (evaluated on sheet_surface(sheet)) to the sheet, and says where they went.
SheetMapLayout carry_maps(GrowingSheet& sheet, const EvaluatedMaps& maps, const SurfaceDomain& domain);

// The carried maps on `domain` (= sheet_surface(sheet).domain): scalar values as they are, vector
// maps back in each face's 2D frame.
EvaluatedMaps sheet_maps(const GrowingSheet& sheet, const SheetMapLayout& layout, const SurfaceDomain& domain);

}  // namespace physarum
