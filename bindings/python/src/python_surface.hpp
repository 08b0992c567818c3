#pragma once
// plmap.Surface: a Surface<1> or Surface<2> shared with the maps built on it.

#include <plmap/core/surface.hpp>

#include <pybind11/pybind11.h>

#include <memory>
#include <variant>

namespace plmap::python {

namespace py = pybind11;

struct PySurface {
  std::variant<std::shared_ptr<const Surface<1>>, std::shared_ptr<const Surface<2>>> surface;

  int dimension() const { return static_cast<int>(surface.index()) + 1; }
  template <int d>
  const std::shared_ptr<const Surface<d>>& get() const {
    return std::get<d - 1>(surface);
  }
};

/// A Surface, a (vertices, elements) pair of arrays, or a path (str or os.PathLike) read as a
/// surface file; anything else is a
/// TypeError naming `what`.
PySurface surface_argument(py::handle value, const char* what);

/// Reads a surface file; dimension 0 guesses it (curve files and Gmsh files without triangles
/// are curves, everything else triangle surfaces).
PySurface read_any_surface(const std::string& path, int dimension);

void bind_surface(py::module_& m);

}  // namespace plmap::python
