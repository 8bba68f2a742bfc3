// The extension module `physarum._physarum`; the package physarum/ (tools/python/physarum/) wraps it
// with the Python-side API (docs/python.md). The engine's errors become Python's: bad input
// (InputError, UsageError) ValueError, a device's failure (DeviceError) RuntimeError, each with the
// engine's message.
#include "common/base/errors.hpp"
#include "tools/python/bindings.hpp"

#include <new>

namespace nb = nanobind;

NB_MODULE(_physarum, m) {
  m.doc() = "physarum's engine, bound with nanobind (import physarum, not this module)";
  nb::register_exception_translator([](const std::exception_ptr& error, void*) {
    try {
      std::rethrow_exception(error);
    } catch (const physarum::DeviceError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const physarum::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const physarum::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  physarum::python::bind_surface(m);
  physarum::python::bind_simulation(m);
  physarum::python::bind_commands(m);
  physarum::python::bind_tools(m);
}
