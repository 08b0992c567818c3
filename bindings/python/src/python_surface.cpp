#include "python_surface.hpp"

#include "numpy_arrays.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/core/io/surface_writer.hpp>
#include <plmap/core/vertex_merging.hpp>
#include <plmap/verify/self_intersections.hpp>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string_view>
#include <type_traits>

namespace plmap::python {

namespace {

template <int d>
PySurface surface_from_arrays(const py::array_t<double>& vertices, const py::array_t<std::int64_t>& elements) {
  const auto v = vertices.unchecked<2>();
  std::vector<WorldPoint<d>> points(v.shape(0));
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    for (int k = 0; k <= d; ++k) points[i](k) = v(i, k);
  const auto e = elements.unchecked<2>();
  std::vector<ElementCorners<d>> corners(e.shape(0));
  for (py::ssize_t t = 0; t < e.shape(0); ++t)
    for (int k = 0; k <= d; ++k) {
      const std::int64_t index = e(t, k);
      // Checked here: the narrowing to plmap::Index below would otherwise wrap large values.
      if (index < 0 || index >= v.shape(0))
        throw py::index_error("elements[" + std::to_string(t) + ", " + std::to_string(k) + "] = " +
                              std::to_string(index) + " is not a vertex index (there are " +
                              std::to_string(v.shape(0)) + " vertices)");
      corners[t][k] = static_cast<Index>(index);
    }
  py::gil_scoped_release unlocked;  // validation and adjacency of a large surface take a while
  return {std::make_shared<const Surface<d>>(std::move(points), std::move(corners))};
}

PySurface surface_from_python_arrays(py::handle vertices_in, py::handle elements_in) {
  const auto vertices = float_matrix(vertices_in, "vertices", -1);
  const py::ssize_t width = vertices.shape(1);
  if (width != 2 && width != 3)
    throw py::value_error("vertices: expected shape (n, 3) for a triangle surface or (n, 2) for a "
                          "curve, got (" + std::to_string(vertices.shape(0)) + ", " +
                          std::to_string(width) + ")");
  const auto elements = index_matrix(elements_in, "elements", static_cast<int>(width));
  if (width == 2) return surface_from_arrays<1>(vertices, elements);
  return surface_from_arrays<2>(vertices, elements);
}

template <int d>
py::array_t<double> vertex_array(const Surface<d>& s) {
  py::array_t<double> out(std::vector<py::ssize_t>{s.vertex_count(), d + 1});
  auto o = out.mutable_unchecked<2>();
  for (Index i = 0; i < s.vertex_count(); ++i)
    for (int k = 0; k <= d; ++k) o(i, k) = s.vertex(i)(k);
  return out;
}

template <int d>
py::array_t<Index> element_array(const Surface<d>& s) {
  py::array_t<Index> out(std::vector<py::ssize_t>{s.element_count(), d + 1});
  auto o = out.mutable_unchecked<2>();
  for (Index t = 0; t < s.element_count(); ++t)
    for (int k = 0; k <= d; ++k) o(t, k) = s.element(t)[k];
  return out;
}

template <class F>
decltype(auto) visit_surface(const PySurface& s, F&& f) {
  return std::visit([&](const auto& ptr) -> decltype(auto) { return f(*ptr); }, s.surface);
}

}  // namespace

PySurface read_any_surface(const std::string& path, int dimension) {
  if (dimension < 0 || dimension > 2)
    throw py::value_error("read_surface: dimension must be 1, 2 or None, got " + std::to_string(dimension));
  py::gil_scoped_release unlocked;
  if (dimension == 1) return {std::make_shared<const Surface<1>>(read_surface<1>(path))};
  if (dimension == 2) return {std::make_shared<const Surface<2>>(read_surface<2>(path))};
  const auto format = format_from_extension(path);
  if (format && !format_supports_dimension(*format, 2))
    return {std::make_shared<const Surface<1>>(read_surface<1>(path))};
  if (format && format_supports_dimension(*format, 1)) {
    // Gmsh files hold either dimension: one without triangles is a curve.
    try {
      return {std::make_shared<const Surface<2>>(read_surface<2>(path))};
    } catch (const ParseError& e) {
      if (std::string_view(e.what()).find("no triangle elements") == std::string_view::npos) throw;
      return {std::make_shared<const Surface<1>>(read_surface<1>(path))};
    }
  }
  return {std::make_shared<const Surface<2>>(read_surface<2>(path))};
}

PySurface surface_argument(py::handle value, const char* what) {
  if (py::isinstance<PySurface>(value)) return py::cast<PySurface>(value);
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return read_any_surface(py::cast<std::filesystem::path>(value).string(), 0);
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    const auto pair = py::reinterpret_borrow<py::sequence>(value);
    if (pair.size() != 2)
      throw py::type_error(std::string(what) + ": expected a (vertices, elements) pair of arrays, got a sequence of " +
                           std::to_string(pair.size()) + " items");
    return surface_from_python_arrays(pair[0], pair[1]);
  }
  throw py::type_error(std::string(what) + ": expected a plmap.Surface or a file path (or a (vertices, elements) pair of arrays), got " +
                       py::cast<std::string>(py::type::of(value).attr("__name__")));
}

void bind_surface(py::module_& m) {
  py::class_<PySurface>(m, "Surface",
                        "A simplicial surface: a triangle surface in space (d = 2) or a curve in the "
                        "plane (d = 1). Immutable; validated on construction.")
      .def(py::init(&surface_from_python_arrays), py::arg("vertices"), py::arg("elements"),
           "Surface(vertices, elements): vertices (n, 3) and triangles (m, 3) for d = 2, or "
           "vertices (n, 2) and segments (m, 2) for d = 1. Element entries are 0-based vertex "
           "indices (any integer dtype).")
      .def_property_readonly("dimension", &PySurface::dimension)
      .def_property_readonly("vertices", [](const PySurface& s) {
        return visit_surface(s, [](const auto& surface) { return vertex_array(surface); });
      }, "Vertex positions, (n, d+1) float64 (a copy)")
      .def_property_readonly("elements", [](const PySurface& s) {
        return visit_surface(s, [](const auto& surface) { return element_array(surface); });
      }, "Element corners, (m, d+1) int32 (a copy)")
      .def_property_readonly("vertex_count", [](const PySurface& s) {
        return visit_surface(s, [](const auto& surface) { return surface.vertex_count(); });
      })
      .def_property_readonly("element_count", [](const PySurface& s) {
        return visit_surface(s, [](const auto& surface) { return surface.element_count(); });
      })
      .def_property_readonly("measure", [](const PySurface& s) {
        return visit_surface(s, [](const auto& surface) { return surface.measure(); });
      }, "Total length (d = 1) or area (d = 2)")
      .def("self_intersections", [](const PySurface& s, unsigned threads) {
        py::gil_scoped_release unlocked;
        return visit_surface(s, [&](const auto& surface) { return plmap::self_intersections(surface, threads); });
      }, py::arg("threads") = 0,
         "Pairs (a, b), a < b, of elements that meet although they share no vertex: where the "
         "surface crosses itself (overlapping bodies in one file). Sorted list of tuples; CGAL's "
         "exact predicates decide; threads=0 uses all cores.")
      .def("merge_coincident_vertices", [](const PySurface& s) {
        return visit_surface(s, [&](const auto& surface) {
          using SurfaceType = std::decay_t<decltype(surface)>;
          VertexMergeReport report;
          SurfaceType merged;
          {
            py::gil_scoped_release unlocked;
            merged = plmap::merge_coincident_vertices(surface, &report);
          }
          return py::make_tuple(PySurface{std::make_shared<const SurfaceType>(std::move(merged))},
                                report.merged_vertices, report.duplicate_elements);
        });
      },
         "(surface, merged_vertices, duplicate_elements): the surface with every vertex at exactly "
         "the position of an earlier one merged into it, and elements that then have the same "
         "corners kept once (welds a polygon soup or an unstitched seam, which normal projection "
         "cannot walk across). Positions are compared exactly; vertex and element order are kept.")
      .def("save", [](const PySurface& s, const std::filesystem::path& path) {
        py::gil_scoped_release unlocked;
        visit_surface(s, [&](const auto& surface) { write_surface(path, surface); });
      }, py::arg("path"),
         "Writes the surface; the format comes from the extension (.off .obj .stl .ply .msh "
         ".curve). The file is replaced atomically.")
      .def("__repr__", [](const PySurface& s) {
        return visit_surface(s, [&](const auto& surface) {
          return "<plmap.Surface d=" + std::to_string(s.dimension()) + ", " +
                 std::to_string(surface.vertex_count()) + " vertices, " +
                 std::to_string(surface.element_count()) + " elements>";
        });
      });

  m.def("read_surface", [](const std::filesystem::path& path, std::optional<int> dimension) {
    return read_any_surface(path.string(), dimension.value_or(0));
  }, py::arg("path"), py::arg("dimension") = py::none(),
     "Reads a surface file (.off .obj .stl .ply .msh .curve). dimension=None guesses: .curve "
     "files and Gmsh files without triangles are curves (d = 1).");
}

}  // namespace plmap::python
