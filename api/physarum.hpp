#pragma once
// The library's public headers, in the order a program uses them (docs/library.md):
//
//   scene      common/scene/scene.hpp        load_scene (a file), scene_from_json (built in code),
//                                            validate_scene; Scene holds the model as a variant
//   surface    common/surface/prepared_surface.hpp   prepare_surface: a mesh or shape:NAME refined
//   session    api/session.hpp               a scene on its surface with its model's backend: step,
//                                            fields on intrinsic and input vertices, save, restore
//   backends   api/backend_factory.hpp       choose_backend, make_backend (for code that brings
//                                            its own surface and arrays: benchmarks, the harness)
//   analysis   common/pattern/pattern_analysis.hpp   spot and stripe measures of a field
//   compare    api/comparison.hpp            the differential harness: two arms, one verdict
//
// `physarum` (tools/) is a client of these headers; so are the benchmarks and the tests.
#include "api/backend_factory.hpp"
#include "api/comparison.hpp"
#include "api/session.hpp"
#include "common/pattern/pattern_analysis.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/prepared_surface.hpp"
