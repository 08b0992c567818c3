// The compiled part of the Python package `plmap` (bindings/python/plmap/__init__.py imports it).

#include "python_map.hpp"
#include "python_surface.hpp"

#include <plmap/core/errors.hpp>

#include <pybind11/pybind11.h>

namespace plmap::python {
void bind_project(py::module_& m);
}

PYBIND11_MODULE(_plmap, m) {
  namespace py = pybind11;
  using namespace plmap;
  m.doc() = "plmap: piecewise-linear maps between simplicial surfaces (compiled part)";

  // plmap::Error and its subclasses become plmap.Error (a ValueError: they are raised for bad
  // input) and its subclasses, with the library's message. Registered base first: pybind11 tries
  // the translators in reverse order, so the most specific one wins.
  auto& error = py::register_exception<Error>(m, "Error", PyExc_ValueError);
  py::register_exception<ParseError>(m, "ParseError", error.ptr());
  py::register_exception<InvalidSurfaceError>(m, "InvalidSurfaceError", error.ptr());
  py::register_exception<BuilderError>(m, "BuilderError", error.ptr());
  py::register_exception<InvalidMapError>(m, "InvalidMapError", error.ptr());

  python::bind_surface(m);
  python::bind_map(m);
  python::bind_ray_check(m);
  python::bind_project(m);
  m.attr("__version__") = PLMAP_VERSION;
}
