#pragma once
// The parts of the module `physarum._physarum`, each in its own file; module.cpp calls them in order.
#include <nanobind/nanobind.h>

namespace physarum::python {

namespace nb = nanobind;

void bind_surface(nanobind::module_& m);     // read_mesh, _Surface: prepared surfaces and their maps
void bind_simulation(nanobind::module_& m);  // _Simulation: a scene's run, stepped from Python
void bind_commands(nanobind::module_& m);    // devices, the command line run in-process

}  // namespace physarum::python
