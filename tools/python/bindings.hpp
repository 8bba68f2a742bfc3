#pragma once
// The parts of the module `physarum._physarum`, each in its own file; module.cpp calls them in order.
#include "api/tools/run_analysis.hpp"
#include "common/surface/prepared_surface.hpp"

#include <nanobind/nanobind.h>

#include <optional>
#include <string>

namespace physarum::python {

namespace nb = nanobind;

void bind_surface(nanobind::module_& m);     // read_mesh, _Surface: prepared surfaces and their maps
void bind_simulation(nanobind::module_& m);  // _Simulation: a scene's run, stepped from Python
void bind_commands(nanobind::module_& m);    // devices
void bind_tools(nanobind::module_& m);       // analyze, compare, colormap, sketch on the library

// The engine's lines handed to `log` (a Python callable taking a line: the package's logger), from
// whichever thread the engine is on; none: quiet.
SurfaceNote python_log(nb::object log);

// analyze()'s arguments as the library takes them.
PatternAnalysisRequest analysis_request(const std::string& field, std::optional<double> threshold, bool below,
                                        double min_area);

}  // namespace physarum::python
