// plmap.project(s1, s2, **options): normal projection (construct/project.hpp) from Python.

#include "keyword_options.hpp"
#include "numpy_arrays.hpp"
#include "python_map.hpp"
#include "python_surface.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/construct/projection_report_json.hpp>

#include <pybind11/numpy.h>

#include <optional>

namespace plmap::python {

namespace {

/// The keyword arguments of project(): the ProjectionOptions, with the directions kept as the
/// array they came as until the dimension is known (to check their shape).
struct ProjectCall {
  ProjectionOptions options;
  std::optional<py::array_t<double>> directions;
};

template <class T>
KeywordField<ProjectCall> option_field(T ProjectionOptions::*member, std::string expected) {
  return {std::move(expected), [member](ProjectCall& c, py::handle v) { c.options.*member = py::cast<T>(v); }};
}

const KeywordFields<ProjectCall>& projection_fields() {
  using O = ProjectionOptions;
  static const KeywordFields<ProjectCall> fields = {
      {"directions", {"an array of shape (S1 vertices, d+1)", [](ProjectCall& c, py::handle v) {
         c.directions = float_matrix(v, "project(): directions", -1);
       }}},
      {"solver", option_field(&O::solver, "a str ('newton' or 'ceres')")},
      {"solver_tolerance", option_field(&O::solver_tolerance, "a float")},
      {"max_distance", option_field(&O::max_distance, "a float")},
      {"max_distance_is_relative", option_field(&O::max_distance_is_relative, "a bool")},
      {"allow_negative_distance", option_field(&O::allow_negative_distance, "a bool")},
      {"normal_check", {"a str ('none', 'facing' or 'aligned')", [](ProjectCall& c, py::handle v) {
         c.options.normal_check = normal_check_argument("project", py::cast<std::string>(v));
       }}},
      {"threads", option_field(&O::threads, "a non-negative int (0: all cores)")},
      {"search_seeds", option_field(&O::search_seeds, "an int")},
      {"snap_tolerance", option_field(&O::snap_tolerance, "a float")},
      {"orientation", option_field(&O::orientation, "an int (0, 1 or -1)")},
      {"keep_nearer_sheet", option_field(&O::keep_nearer_sheet, "a bool")},
      {"renumbering", {"a str ('auto', 'always', 'target' or 'never')", [](ProjectCall& c, py::handle v) {
         const std::string name = py::cast<std::string>(v);
         const auto r = spatial_renumbering_from_name(name);
         if (!r) throw py::value_error("project(): renumbering must be 'auto', 'always', 'target' or 'never', got '" + name + "'");
         c.options.renumbering = *r;
       }}},
  };
  return fields;
}

template <int d>
PyMap project_surfaces(const PySurface& s1, const PySurface& s2, ProjectCall call) {
  ProjectionOptions& options = call.options;
  if (call.directions) {
    const py::array_t<double>& a = *call.directions;
    if (a.shape(1) != d + 1 || a.shape(0) != s1.get<d>()->vertex_count())
      throw py::value_error("project(): directions must have shape (" +
                            std::to_string(s1.get<d>()->vertex_count()) + ", " + std::to_string(d + 1) +
                            ") (one per S1 vertex), got (" + std::to_string(a.shape(0)) + ", " +
                            std::to_string(a.shape(1)) + ")");
    options.directions.assign(a.data(), a.data() + a.size());
  }
  std::optional<ProjectionResult<d>> result;
  {
    py::gil_scoped_release unlocked;
    result.emplace(project<d>(s1.get<d>(), s2.get<d>(), options));
  }
  PyMap out;
  // the report first: it counts the map's regions and nodes
  out.report = json_to_python(projection_report_json(*result));
  out.map = std::make_shared<const PlMap<d>>(std::move(result->map));
  return out;
}

PyMap project_any(py::handle s1_in, py::handle s2_in, const py::kwargs& kwargs) {
  ProjectCall call;
  call.options.threads = 0;  // all cores, as every plmap command defaults to
  apply_keyword_options("project", kwargs, projection_fields(), call);
  const PySurface s1 = surface_argument(s1_in, "project(): s1");
  const PySurface s2 = surface_argument(s2_in, "project(): s2");
  if (s1.dimension() != s2.dimension())
    throw py::value_error("project(): s1 has dimension " + std::to_string(s1.dimension()) +
                          " but s2 has dimension " + std::to_string(s2.dimension()));
  if (s1.dimension() == 1) return project_surfaces<1>(s1, s2, std::move(call));
  return project_surfaces<2>(s1, s2, std::move(call));
}

}  // namespace

void bind_project(py::module_& m) {
  m.def("project", &project_any, py::arg("s1"), py::arg("s2"),
        "Maps S1 to S2 by normal projection (paper section 3.2) and returns the plmap.Map "
        "D ⊂ S1 -> S2; map.report says what was built and what not. s1, s2: plmap.Surface or file "
        "paths or (vertices, elements) pairs of arrays. Keyword options are the fields of plmap::ProjectionOptions: directions ((n1, d+1) "
        "array), solver, solver_tolerance, max_distance, max_distance_is_relative, "
        "allow_negative_distance, normal_check ('none', 'facing', 'aligned'), threads (default 0: "
        "all cores), search_seeds, snap_tolerance, orientation, keep_nearer_sheet, renumbering "
        "('auto', 'always', 'target', 'never': copies in spatial order; the map is in the input's numbers).");
}

}  // namespace plmap::python
