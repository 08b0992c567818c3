#pragma once
// plmap.Map: a finalized PlMap<1> or PlMap<2>, with the report of the construction that made it.

#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/pl_map.hpp>

#include <nlohmann/json.hpp>
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

/// f(map) for the PlMap<1> or PlMap<2> that `m` holds.
template <class F>
decltype(auto) visit_map(const PyMap& m, F&& f) {
  return std::visit([&](const auto& ptr) -> decltype(auto) { return f(*ptr); }, m.map);
}

/// A JSON value as the Python object json.loads makes of it (dicts, lists, numbers, str; an
/// ordered_json's objects keep their order).
template <class Json>
py::object json_to_python(const Json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

void bind_map(py::module_& m);
/// Map.check_against_rays (python_ray_check.cpp); after bind_map.
void bind_ray_check(py::module_& m);

}  // namespace plmap::python
