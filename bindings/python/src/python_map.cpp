#include "python_map.hpp"

#include "keyword_options.hpp"
#include "numpy_arrays.hpp"
#include "python_surface.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/facts_json.hpp>
#include <plmap/verify/quality.hpp>
#include <plmap/verify/report_json.hpp>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>

namespace plmap::python {

namespace {

const KeywordFields<VerifyOptions>& verify_fields() {
  static const KeywordFields<VerifyOptions> fields = {
      {"snap_tolerance", keyword_field(&VerifyOptions::snap_tolerance, "a float")},
      {"local_tolerance", keyword_field(&VerifyOptions::local_tolerance, "a float")},
      {"world_tolerance", keyword_field(&VerifyOptions::world_tolerance, "a float")},
      {"measure_tolerance", keyword_field(&VerifyOptions::measure_tolerance, "a float")},
      {"continuity_samples_per_piece", keyword_field(&VerifyOptions::continuity_samples_per_piece, "an int")},
      {"expect_parametrization", keyword_field(&VerifyOptions::expect_parametrization, "a bool")},
      {"max_condition", keyword_field(&VerifyOptions::max_condition, "a float")},
      {"compute_quality", keyword_field(&VerifyOptions::compute_quality, "a bool")},
      {"max_reported_per_rule", keyword_field(&VerifyOptions::max_reported_per_rule, "an int")},
  };
  return fields;
}

// ---- evaluate ------------------------------------------------------------------------------

/// Local coordinates may leave the reference element by this much (they are scale-free, so this
/// is relative to the element) before a query point counts as malformed.
constexpr double local_slack = 1e-9;

/// The query points as two checked arrays: elements (n,) int64 and local coordinates (n, d).
struct QueryArrays {
  py::array_t<std::int64_t> elements;
  py::array_t<double> local;
};

/// Checks the query points against `surface` (S1 for evaluate, S2 for inverse); `what` names the
/// call and the surface in messages.
template <int d>
QueryArrays query_arrays(const Surface<d>& surface, const char* what, const char* surface_name,
                         py::handle elements_in, py::handle local_in) {
  QueryArrays q;
  q.elements = index_matrix(elements_in, "elements", 0);
  // d = 1 also takes local coordinates as a flat (n,) array.
  q.local = [&] {
    if (d == 1) {
      auto flat = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(local_in);
      if (flat && flat.ndim() == 1)
        return py::array_t<double>(flat.reshape(std::vector<py::ssize_t>{flat.shape(0), 1}));
    }
    return float_matrix(local_in, "local", d);
  }();
  if (q.local.shape(0) != q.elements.shape(0))
    throw py::value_error(std::string(what) + ": " + std::to_string(q.elements.shape(0)) + " elements but " +
                          std::to_string(q.local.shape(0)) + " rows of local coordinates");
  const auto e = q.elements.unchecked<1>();
  const auto x = q.local.unchecked<2>();
  const Index element_count = surface.element_count();
  for (py::ssize_t i = 0; i < e.shape(0); ++i) {
    if (e(i) < 0 || e(i) >= element_count)
      throw py::index_error(std::string(what) + ": elements[" + std::to_string(i) + "] = " + std::to_string(e(i)) +
                            " is not an " + surface_name + " element (" + surface_name + " has " +
                            std::to_string(element_count) + ")");
    double sum = 0.0;
    bool inside = true;
    for (int k = 0; k < d; ++k) {
      sum += x(i, k);
      inside = inside && std::isfinite(x(i, k)) && x(i, k) >= -local_slack;
    }
    if (!inside || sum > 1.0 + local_slack)
      throw py::value_error(std::string(what) + ": local[" + std::to_string(i) +
                            "] is not a point of the reference element (coordinates >= 0 with sum <= 1)");
  }
  return q;
}

/// Points evaluated per thread and call of evaluate_batch: the library's batch works on buffers
/// of this size, reused, instead of on temporary copies of all points (whose fresh pages cost as
/// much as the evaluation itself for millions of points).
constexpr std::size_t points_per_thread_and_batch = std::size_t{1} << 16;

/// Whether a forward or inverse evaluation found its point, and the point on the other surface.
template <int d>
bool found(const Evaluation<d>& e) { return e.in_domain; }
template <int d>
const SurfacePoint<d>& answer_point(const Evaluation<d>& e) { return e.image; }
template <int d>
bool found(const InverseEvaluation<d>& e) { return e.in_image; }
template <int d>
const SurfacePoint<d>& answer_point(const InverseEvaluation<d>& e) { return e.preimage; }

/// The answers of evaluate and inverse as numpy arrays, one row per query point: found, region,
/// the point on the other surface (element, local coordinates) and its world position; -1 and
/// NaN where the point was not found.
template <int d>
struct AnswerArrays {
  py::array_t<bool> found;
  py::array_t<Index> region, element;
  py::array_t<double> local, world;

  explicit AnswerArrays(py::ssize_t n)
      : found(n), region(n), element(n), local(std::vector<py::ssize_t>{n, d}),
        world(std::vector<py::ssize_t>{n, d + 1}) {}

  py::dict to_dict(const char* found_key, const char* element_key, const char* local_key) const {
    py::dict result;
    result[found_key] = found;
    result["region"] = region;
    result[element_key] = element;
    result[local_key] = local;
    result["world"] = world;
    return result;
  }
};

/// Answers the queries `q` in batches of reused buffers: `solve(points, out)` evaluates one batch
/// (on its threads). Call without the GIL: it touches only raw pointers into arrays the caller's
/// frame owns.
template <int d, class Result, class Solve>
void answer_in_batches(const QueryArrays& q, unsigned threads, AnswerArrays<d>& a, Solve&& solve) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const py::ssize_t n = q.elements.shape(0);
  const std::int64_t* e_in = q.elements.data();
  const double* x_in = q.local.data();
  bool* in = a.found.mutable_data();
  Index* r = a.region.mutable_data();
  Index* el = a.element.mutable_data();
  double* lo = a.local.mutable_data();
  double* w = a.world.mutable_data();
  const unsigned workers = resolve_thread_count(threads);
  const std::size_t points_per_batch = points_per_thread_and_batch * workers;
  std::vector<SurfacePoint<d>> points;
  std::vector<Result> out;
  for (py::ssize_t begin = 0; begin < n;) {
    const auto count = static_cast<py::ssize_t>(std::min<std::size_t>(points_per_batch, n - begin));
    points.resize(count);
    out.resize(count);
    for (py::ssize_t i = 0; i < count; ++i) {
      points[i].element = static_cast<Index>(e_in[begin + i]);
      for (int k = 0; k < d; ++k) points[i].local(k) = x_in[(begin + i) * d + k];
    }
    solve(std::span<const SurfacePoint<d>>(points), std::span<Result>(out));
    for (py::ssize_t i = 0; i < count; ++i) {
      const Result& ev = out[i];
      const bool ok = found(ev);
      const py::ssize_t j = begin + i;
      in[j] = ok;
      r[j] = ok ? ev.region : invalid_index;
      el[j] = ok ? answer_point(ev).element : invalid_index;
      for (int k = 0; k < d; ++k) lo[j * d + k] = ok ? answer_point(ev).local(k) : nan;
      for (int k = 0; k <= d; ++k) w[j * (d + 1) + k] = ok ? ev.world(k) : nan;
    }
    begin += count;
  }
}

template <int d>
py::dict evaluate_points(const PlMap<d>& map, py::handle elements, py::handle local,
                         const std::optional<std::string>& locator_name, unsigned threads) {
  const QueryArrays q = query_arrays(map.domain(), "evaluate", "S1", elements, local);
  const std::string name(locator_name ? *locator_name : std::string(default_point_locator_name<d>()));
  AnswerArrays<d> answers(q.elements.shape(0));
  {
    py::gil_scoped_release unlocked;
    with_point_locator<d>(name, [&](auto& locator) {
      answer_in_batches<d, Evaluation<d>>(q, threads, answers, [&](auto points, auto out) {
        evaluate_batch<d>(map, points, out, locator, threads);
      });
    });
  }
  return answers.to_dict("in_domain", "image_element", "image_local");
}

// ---- inverse -------------------------------------------------------------------------------

template <int d>
const InverseIndex<d>& inverse_index_of(PyMap& pm, const PlMap<d>& map) {
  using Held = std::shared_ptr<const InverseIndex<d>>;
  if (!std::holds_alternative<Held>(pm.inverse_index)) {
    Held built;
    {
      py::gil_scoped_release unlocked;
      built = std::make_shared<const InverseIndex<d>>(map);
    }
    pm.inverse_index = std::move(built);  // with the GIL: another Python thread may call too
  }
  return *std::get<Held>(pm.inverse_index);
}

template <int d>
py::dict inverse_points(PyMap& pm, const PlMap<d>& map, py::handle elements, py::handle local,
                        unsigned threads) {
  const QueryArrays q = query_arrays(map.target(), "inverse", "S2", elements, local);
  const InverseIndex<d>& index = inverse_index_of(pm, map);
  AnswerArrays<d> answers(q.elements.shape(0));
  {
    py::gil_scoped_release unlocked;
    answer_in_batches<d, InverseEvaluation<d>>(q, threads, answers, [&](auto points, auto out) {
      inverse_evaluate_batch<d>(index, points, out, threads);
    });
  }
  return answers.to_dict("in_image", "preimage_element", "preimage_local");
}

// ---- regions, quality, summary --------------------------------------------------------------

template <int d>
py::dict region_arrays(const PlMap<d>& map) {
  const auto n = static_cast<py::ssize_t>(map.region_count());
  py::array_t<Index> domain_element(n), target_element(n);
  py::array_t<double> domain_local(std::vector<py::ssize_t>{n, d + 1, d});
  py::array_t<double> target_local(std::vector<py::ssize_t>{n, d + 1, d});
  py::array_t<double> domain_measure(n), target_measure(n);
  // Raw pointers, so the loop runs without the GIL (the arrays are owned by this frame).
  Index* de = domain_element.mutable_data();
  Index* te = target_element.mutable_data();
  double* dl = domain_local.mutable_data();
  double* tl = target_local.mutable_data();
  double* dm = domain_measure.mutable_data();
  double* tm = target_measure.mutable_data();
  {
    py::gil_scoped_release unlocked;
    for (Index t = 0; t < map.domain().element_count(); ++t)
      for (Index region = map.regions_begin(t); region < map.regions_end(t); ++region) {
        const RemoteIntersection<d> ri = remote_intersection(map, region);
        de[region] = ri.domain_element;
        te[region] = ri.target_element;
        for (int c = 0; c <= d; ++c)
          for (int k = 0; k < d; ++k) {
            dl[(region * (d + 1) + c) * d + k] = ri.domain_local[c](k);
            tl[(region * (d + 1) + c) * d + k] = ri.target_local[c](k);
          }
        dm[region] = ri.domain_measure();
        tm[region] = ri.target_measure();
      }
  }
  py::dict out;
  out["domain_element"] = domain_element;
  out["target_element"] = target_element;
  out["domain_local"] = domain_local;
  out["target_local"] = target_local;
  out["domain_measure"] = domain_measure;
  out["target_measure"] = target_measure;
  return out;
}

template <int d>
py::array_t<double> region_kappa(const PlMap<d>& map) {
  py::array_t<double> out(static_cast<py::ssize_t>(map.region_count()));
  double* k = out.mutable_data();
  py::gil_scoped_release unlocked;
  for (Index r = 0; r < map.region_count(); ++r) k[r] = region_conditioning(map, r).kappa;
  return out;
}

template <int d>
py::object map_facts(const PlMap<d>& map, bool quality) {
  nlohmann::ordered_json j;
  {
    py::gil_scoped_release unlocked;
    j = map_facts_json(map, quality);
  }
  return json_to_python(j);
}

PyMap load_any_map(const std::filesystem::path& path, py::handle s1_in, py::handle s2_in) {
  if (s1_in.is_none() != s2_in.is_none())
    throw py::type_error("load(): give both surfaces s1 and s2 (to check the map against them) or neither");
  decltype(PyMap::map) loaded;
  if (s1_in.is_none()) {
    py::gil_scoped_release unlocked;
    loaded = std::visit([](auto&& map) -> decltype(PyMap::map) {
      using M = std::decay_t<decltype(map)>;
      return std::make_shared<const M>(std::move(map));
    }, load_map(path));
  } else {
    const PySurface s1 = surface_argument(s1_in, "load(): s1");
    const PySurface s2 = surface_argument(s2_in, "load(): s2");
    const int stored = map_file_dimension(path);
    for (const auto& [given, name] : {std::pair{&s1, "s1"}, std::pair{&s2, "s2"}})
      if (given->dimension() != stored)
        throw py::value_error("load(): " + path.string() + " holds a map of dimension " + std::to_string(stored) +
                              ", but " + name + " has dimension " + std::to_string(given->dimension()));
    py::gil_scoped_release unlocked;
    // load_map checks both surfaces against the fingerprints stored in the file and refuses a
    // mismatch with a ParseError naming the file and the surface (domain (S1) or target (S2)).
    if (stored == 1)
      loaded = std::make_shared<const PlMap<1>>(load_map<1>(path, s1.get<1>(), s2.get<1>()));
    else
      loaded = std::make_shared<const PlMap<2>>(load_map<2>(path, s1.get<2>(), s2.get<2>()));
  }
  PyMap out;  // with the GIL: PyMap holds a Python object
  out.map = std::move(loaded);
  return out;
}

}  // namespace

void bind_map(py::module_& m) {
  py::class_<PyMap>(m, "Map",
                    "A piecewise-linear map Xi: D ⊂ S1 -> S2 (immutable). Made by plmap.project or "
                    "plmap.load.")
      .def_property_readonly("dimension", &PyMap::dimension)
      .def_property_readonly("domain", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return PySurface{map.domain_ptr()}; });
      }, "S1, the surface the map is stored on")
      .def_property_readonly("target", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return PySurface{map.target_ptr()}; });
      }, "S2")
      .def_property_readonly("region_count", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return map.region_count(); });
      })
      .def_property_readonly("node_count", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return map.node_count(); });
      })
      .def_readonly("report", &PyMap::report,
                    "What plmap.project reported, as a dict with the keys and values of `plmap project "
                    "--json` (counts, left_out_measure, every S2 edge not inserted and why in "
                    "edges_not_inserted_list, seconds and seconds_by_phase); None for a loaded map")
      .def("save", [](const PyMap& pm, const std::filesystem::path& path) {
        py::gil_scoped_release unlocked;
        visit_map(pm, [&](const auto& map) { save_map(path, map); });
      }, py::arg("path"), "Writes the map file, replacing `path` atomically: binary for a .plmapb path, text (.plmap) otherwise.")
      .def("check", [](const PyMap& pm, const py::kwargs& kwargs) {
        VerifyOptions options;
        apply_keyword_options("check", kwargs, verify_fields(), options);
        const VerificationReport report = visit_map(pm, [&](const auto& map) {
          py::gil_scoped_release unlocked;
          return verify(map, options);
        });
        return json_to_python(to_json(report));
      }, "Checks every invariant (DESIGN.md §4) and returns the report as a dict: 'ok', "
         "'violation_count', 'checks' (per check: rules and the violations named), 'quality'. "
         "Keyword arguments are the fields of plmap::VerifyOptions (e.g. expect_parametrization=True).")
      .def("evaluate", [](const PyMap& pm, py::handle elements, py::handle local,
                          const std::optional<std::string>& locator, unsigned threads) {
        return visit_map(pm, [&](const auto& map) { return evaluate_points(map, elements, local, locator, threads); });
      }, py::arg("elements"), py::arg("local"), py::kw_only(), py::arg("locator") = py::none(),
         py::arg("threads") = 0u,
         "Xi at the points (elements[i], local[i]) of S1: elements (n,) int, local (n, d) local "
         "coordinates on the element (d = 1: also (n,)). Runs on `threads` threads (0: all cores) without the GIL. "
         "Returns a dict of arrays: in_domain (n,) bool, region (n,), image_element (n,) (-1 "
         "outside D), image_local (n, d), world (n, d+1) (NaN outside D). `locator` names the "
         "point-location strategy (default: brown-faigle for d = 2, bisection for d = 1).")
      .def("inverse", [](PyMap& pm, py::handle elements, py::handle local, unsigned threads) {
        return visit_map(pm, [&](const auto& map) { return inverse_points(pm, map, elements, local, threads); });
      }, py::arg("elements"), py::arg("local"), py::kw_only(), py::arg("threads") = 0u,
         "Xi^-1 at the points (elements[i], local[i]) of S2: elements (n,) int, local (n, d) local "
         "coordinates on the S2 element (d = 1: also (n,)). The S2 -> regions index is built on the "
         "first call and kept. Runs on `threads` threads (0: all cores) without the GIL. Returns a "
         "dict of arrays: in_image (n,) bool, region (n,), preimage_element (n,) (-1 outside Xi(D)), "
         "preimage_local (n, d), world (n, d+1) on S1 (NaN outside Xi(D)).")
      .def("regions", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return region_arrays(map); });
      }, "The regions (remote intersections T1 ∩ Xi^-1(T2)) as flat arrays, one row per region: "
         "domain_element, target_element (r,) int32; domain_local, target_local (r, d+1, d), the "
         "corners in local coordinates of the two elements, in the same order; domain_measure, "
         "target_measure (r,).")
      .def("kappa", [](const PyMap& pm) {
        return visit_map(pm, [](const auto& map) { return region_kappa(map); });
      }, "The condition number of every region's linear piece, (r,) float64 (inf where a region "
         "is degenerate).")
      .def("info", [](const PyMap& pm, bool quality) {
        return visit_map(pm, [&](const auto& map) { return map_facts(map, quality); });
      }, py::kw_only(), py::arg("quality") = true,
         "What `plmap info MAP --json` reports, as a dict (one function writes both): orientation, "
         "both surfaces' facts, nodes (total and by type), regions, coverage, memory, the "
         "provenance if the map has one (project() records its acceptance rules there) and "
         "(with quality=True) the distribution of kappa.")
      .def("__repr__", [](const PyMap& pm) {
        return visit_map(pm, [&](const auto& map) {
          return "<plmap.Map d=" + std::to_string(pm.dimension()) + ", " +
                 std::to_string(map.domain().element_count()) + " -> " +
                 std::to_string(map.target().element_count()) + " elements, " +
                 std::to_string(map.region_count()) + " regions>";
        });
      });

  m.def("load", &load_any_map, py::arg("path"), py::arg("s1") = py::none(), py::arg("s2") = py::none(),
        "load(path, s1=None, s2=None): loads a map file (.plmap text or .plmapb binary) of either "
        "dimension. With s1 and s2 (each a plmap.Surface, a (vertices, elements) pair of arrays or "
        "a surface file path), the map is checked against them: a surface whose fingerprint "
        "differs from the one stored for it in the file is refused with plmap.ParseError, whose "
        "message names the file and which surface differs ('domain (S1)' or 'target (S2)'); the "
        "returned map then holds the given surfaces (map.domain, map.target).");
}

}  // namespace plmap::python
