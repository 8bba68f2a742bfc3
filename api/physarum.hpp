#pragma once
// The library's public headers, in the order a program uses them (docs/library.md):
//
//   scene      common/scene/scene.hpp        load_scene (a file), scene_from_json (built in code),
//                                            validate_scene; Scene holds the model as one of SceneModel
//   surface    common/surface/prepared_surface.hpp   prepare_surface: a mesh or shape:NAME refined
//   session    api/session.hpp               a scene on its surface with its model's backend: step,
//                                            fields on intrinsic and input vertices, save, restore
//   backends   api/backend_factory.hpp       choose_backend, make_backend (for code that brings
//                                            its own surface and arrays: benchmarks, the harness)
//   analysis   common/pattern/pattern_analysis.hpp   spot and stripe measures of a field
//   run        api/run/prepared_run.hpp      a whole `physarum run` (run_to_files), or a run stepped
//                                            by its caller (prepare_run, loop(), write)
//   compare    api/comparison.hpp            the differential harness: two arms, one verdict
//   tools      api/tools/run_analysis.hpp, api/tools/color_map_from_image.hpp, api/sketch/sketch_run.hpp
//                                            analyze, colormap and sketch as functions
//   models     api/models/model_table.hpp    the table of models (docs/library.md, "A new model")
//
// `physarum` (tools/) is a client of these headers; so are the benchmarks and the tests.
#include "api/backend_factory.hpp"
#include "api/comparison.hpp"
#include "api/models/model_table.hpp"
#include "api/run/prepared_run.hpp"
#include "api/session.hpp"
#include "api/sketch/sketch_run.hpp"
#include "api/tools/color_map_from_image.hpp"
#include "api/tools/run_analysis.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/prepared_surface.hpp"
