#include "eval_points.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/evaluation_at_boundaries.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/io/atomic_file.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/numeric_table.hpp>
#include <plmap/strategies/nearest_point/nearest_point.hpp>
#include <plmap/strategies/point_locator_registry.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

namespace plmap::cli {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

constexpr std::array<const char*, 3> axis = {"x", "y", "z"};

/// The query points on the surface being evaluated (S1 forwards, S2 backwards), and for world
/// points where they were placed.
template <int d>
struct Queries {
  std::vector<SurfacePoint<d>> points;
  std::vector<double> distance;  ///< world input: distance to the placed point; empty otherwise
};

/// "local" or "world": the flag, else the header's first column name, else local.
std::string points_kind(const EvalPointsOptions& o, const NumericTable& table) {
  if (!o.points_kind.empty()) return o.points_kind;
  if (!table.column_names.empty()) {
    const std::string& first = table.column_names.front();
    if (first == "x") return "world";
    if (first == "element") return "local";
    throw ParseError(o.points_file, "line 1",
                     "header starts with '" + first + "': expected 'element' (local points) or 'x' (world points), or "
                     "give --points-kind");
  }
  return "local";
}

template <int d>
Queries<d> read_queries(const EvalPointsOptions& o, const NumericTable& table, const std::shared_ptr<const Surface<d>>& on,
                        const char* surface_name) {
  const std::string kind = points_kind(o, table);
  const std::size_t expected = d + 1;
  if (table.columns != expected && table.rows > 0)
    throw ParseError(o.points_file, table.row_location(0),
                     fmt::format("expected {} values per point ({} for this map of dimension {}), found {}", expected,
                                 kind == "world" ? (d == 2 ? "x,y,z" : "x,y") : (d == 2 ? "element,u,v" : "element,u"), d,
                                 table.columns));
  Queries<d> q;
  q.points.resize(table.rows);
  if (kind == "local") {
    const double tolerance = 1e-9;  // local coordinates are relative to the element's size
    for (std::size_t r = 0; r < table.rows; ++r) {
      const double element = table(r, 0);
      if (element != std::floor(element) || element < 0 || element >= on->element_count())
        throw ParseError(o.points_file, table.row_location(r),
                         fmt::format("element {} is not an element of {} (it has {} elements)", element, surface_name,
                                     on->element_count()));
      SurfacePoint<d>& p = q.points[r];
      p.element = static_cast<Index>(element);
      for (int i = 0; i < d; ++i) p.local(i) = table(r, 1 + i);
      Barycentric<d> b = barycentric_from_local<d>(p.local);
      if (b.minCoeff() < -tolerance)
        throw ParseError(o.points_file, table.row_location(r),
                         fmt::format("local coordinates lie outside the reference {} (barycentric weight {:.3g} < 0)",
                                     d == 2 ? "triangle" : "segment", b.minCoeff()));
      b = b.cwiseMax(0.0);  // rounding just outside: onto the element
      p.local = local_from_barycentric<d>(b / b.sum());
    }
    return q;
  }
  // World points: the nearest point of the surface (CGAL AABB tree).
  std::vector<WorldPoint<d>> xs(table.rows);
  for (std::size_t r = 0; r < table.rows; ++r)
    for (int i = 0; i <= d; ++i) xs[r](i) = table(r, i);
  std::vector<NearestPoint<d>> nearest(table.rows);
  nearest_points_batch<d>(AabbNearestPoint<d>(on), xs, nearest, o.threads);
  q.distance.resize(table.rows);
  for (std::size_t r = 0; r < table.rows; ++r) q.points[r] = nearest[r].point, q.distance[r] = nearest[r].distance;
  return q;
}

/// One output row per point: found flag, element (-1 if not found), local coordinates and world
/// position of the result (NaN if not found), then for world input the placed query point.
template <int d>
NumericTable result_table(bool inverse, const Queries<d>& q, const std::vector<char>& found,
                          const std::vector<SurfacePoint<d>>& result, const std::vector<WorldPoint<d>>& world) {
  NumericTable t;
  t.column_names = {inverse ? "in_image" : "in_domain", "element"};
  for (int i = 0; i < d; ++i) t.column_names.push_back(i == 0 ? "u" : "v");
  for (int i = 0; i <= d; ++i) t.column_names.push_back(axis[i]);
  const bool world_input = !q.distance.empty();
  if (world_input) {
    t.column_names.push_back("query_element");
    for (int i = 0; i < d; ++i) t.column_names.push_back(i == 0 ? "query_u" : "query_v");
    t.column_names.push_back("query_distance");
  }
  t.columns = t.column_names.size();
  t.rows = q.points.size();
  t.values.reserve(t.rows * t.columns);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t r = 0; r < t.rows; ++r) {
    const bool ok = found[r] != 0;
    t.values.push_back(ok ? 1.0 : 0.0);
    t.values.push_back(ok ? result[r].element : -1.0);
    for (int i = 0; i < d; ++i) t.values.push_back(ok ? result[r].local(i) : nan);
    for (int i = 0; i <= d; ++i) t.values.push_back(ok ? world[r](i) : nan);
    if (world_input) {
      t.values.push_back(q.points[r].element);
      for (int i = 0; i < d; ++i) t.values.push_back(q.points[r].local(i));
      t.values.push_back(q.distance[r]);
    }
  }
  return t;
}

/// JSON: one object per point, NaN as null.
void write_table_json(std::ostream& out, const NumericTable& t, int d, bool inverse) {
  Json j;
  j["dimension"] = d;
  j["direction"] = inverse ? "inverse" : "forward";
  j["points"] = Json::array();
  for (std::size_t r = 0; r < t.rows; ++r) {
    Json p;
    for (std::size_t c = 0; c < t.columns; ++c) {
      const double v = t(r, c);
      const std::string& name = t.column_names[c];
      if (c == 0)
        p[name] = v != 0.0;
      else if (name == "element" || name == "query_element")
        p[name] = static_cast<long long>(v);
      else if (std::isnan(v))
        p[name] = nullptr;
      else
        p[name] = v;
    }
    j["points"].push_back(std::move(p));
  }
  out << j.dump(1) << '\n';
}

template <int d>
int run(const EvalPointsOptions& o, const PlMap<d>& map, const NumericTable& table) {
  const auto start = std::chrono::steady_clock::now();
  const auto& query_surface = o.inverse ? map.target_ptr() : map.domain_ptr();
  const Queries<d> q = read_queries<d>(o, table, query_surface, o.inverse ? "S2" : "S1");
  const std::size_t n = q.points.size();
  std::vector<char> found(n);
  std::vector<SurfacePoint<d>> result(n);
  std::vector<WorldPoint<d>> world(n);
  std::string locator_name;
  if (o.inverse) {
    const InverseIndex<d> index(map);
    std::vector<InverseEvaluation<d>> out(n);
    inverse_evaluate_batch<d>(index, q.points, out, o.threads);
    for (std::size_t i = 0; i < n; ++i) found[i] = out[i].in_image, result[i] = out[i].preimage, world[i] = out[i].world;
  } else {
    locator_name = o.locator.empty() ? std::string(default_point_locator_name<d>()) : o.locator;
    std::vector<Evaluation<d>> out(n);
    // Points on element boundaries (world points placed on an edge, the user's corners) are
    // found from any incident element, as the inverse does.
    with_point_locator<d>(locator_name, [&](auto& locator) { evaluate_points_batch<d>(map, q.points, out, locator, o.threads); });
    for (std::size_t i = 0; i < n; ++i) found[i] = out[i].in_domain, result[i] = out[i].image, world[i] = out[i].world;
  }
  const NumericTable t = result_table<d>(o.inverse, q, found, result, world);
  const std::string ext = lower_extension(o.output);
  if (o.output.empty()) {
    write_table_csv(std::cout, t);
    return exit_code::success;
  }
  write_file_atomically(
      o.output,
      [&](std::ostream& out) {
        if (ext == ".csv")
          write_table_csv(out, t);
        else if (ext == ".json")
          write_table_json(out, t, d, o.inverse);
        else if (ext == ".npy")
          write_table_npy(out, t);
        else
          write_table_raw(out, t);
      },
      ext == ".npy" || ext == ".bin");
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  Json j;
  j["map"] = o.map_file;
  j["points_file"] = o.points_file;
  j["direction"] = o.inverse ? "inverse" : "forward";
  j["points_kind"] = q.distance.empty() ? "local" : "world";
  if (!o.inverse) j["locator"] = locator_name;
  j["points"] = n;
  j[o.inverse ? "in_image" : "in_domain"] = std::count(found.begin(), found.end(), 1);
  j["output"] = o.output;
  j["columns"] = t.column_names;
  j["seconds"] = elapsed.count();
  print_result(j, o.json);
  return exit_code::success;
}

}  // namespace

bool is_known_points_output(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".csv" || ext == ".json" || ext == ".npy" || ext == ".bin";
}

int run_eval_points(const EvalPointsOptions& o) {
  require_readable_file(o.map_file);
  require_readable_file(o.points_file);
  const AnyPlMap map = load_map_showing_progress(o.map_file, o.progress);
  const NumericTable table = read_numeric_table(o.points_file);
  return std::visit([&](const auto& m) { return run(o, m, table); }, map);
}

}  // namespace plmap::cli
