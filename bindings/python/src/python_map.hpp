#pragma once
// plmap.Map: a finalized PlMap<1> or PlMap<2>, with the report of the construction that made it.

#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/pl_map.hpp>

#include <pybind11/pybind11.h>

#include <memory>
#include <variant>

namespace plmap::python {

namespace py = pybind11;

struct PyMap {
  std::variant<std::shared_ptr<const PlMap<1>>, std::shared_ptr<const PlMap<2>>> map;
  /// What plmap.project reported (a dict), None for a loaded map.
  py::object report = py::none();
  /// The S2 -> regions index of Xi^{-1}, built by the first call of Map.inverse and kept (it
  /// holds a reference to the map, which this object keeps alive).
  std::variant<std::monostate, std::shared_ptr<const InverseIndex<1>>,
               std::shared_ptr<const InverseIndex<2>>>
      inverse_index;

  int dimension() const { return static_cast<int>(map.index()) + 1; }
};

void bind_map(py::module_& m);

}  // namespace plmap::python
