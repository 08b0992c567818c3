// refine_through_map(): uniform refinement of S1 on the barycentric lattice of each triangle,
// vertices moved to their images, and the distance of the result to S2 (CGAL AABB tree).

#include <plmap/construct/refine_through_map.hpp>

#include <plmap/core/errors.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/strategies/point_location/brute_force.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <map>
#include <tuple>

namespace plmap {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalTriangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

/// Elements between two progress calls.
constexpr Index progress_every = 4096;

double aspect_ratio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (!(area > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max({la, lb, lc}) * (la + lb + lc) / (4.0 * std::sqrt(3.0) * area);
}

}  // namespace

AspectRatioSummary aspect_ratio_summary(const Surface<2>& surface) {
  std::vector<double> ratios;
  ratios.reserve(surface.element_count());
  for (Index t = 0; t < surface.element_count(); ++t)
    ratios.push_back(aspect_ratio(surface.corner(t, 0), surface.corner(t, 1), surface.corner(t, 2)));
  AspectRatioSummary s;
  if (ratios.empty()) return s;
  std::sort(ratios.begin(), ratios.end());
  auto quantile = [&](double q) { return ratios[static_cast<std::size_t>(q * (ratios.size() - 1) + 0.5)]; };
  s.min = ratios.front();
  s.max = ratios.back();
  double sum = 0.0;
  for (double r : ratios) sum += r;
  s.mean = sum / ratios.size();
  s.p50 = quantile(0.5);
  s.p90 = quantile(0.9);
  s.p99 = quantile(0.99);
  return s;
}

RefineResult refine_through_map(const PlMap<2>& map, const RefineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.levels < 0 || options.levels > 8)
    throw Error(fmt::format("refine: the levels must be between 0 and 8, not {}", options.levels));
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  const int n = 1 << options.levels;

  // A lattice point is shared between triangles when it is an S1 vertex or on an S1 edge; the
  // key names it the same way from every side.
  std::map<std::tuple<int, Index, int>, Index> shared;  // (kind, vertex or edge, step from smaller vertex)
  std::vector<WorldPoint<2>> vertices;
  std::vector<ElementCorners<2>> elements;
  elements.reserve(static_cast<std::size_t>(s1.element_count()) * n * n);
  point_location::BruteForce<2> locator;

  auto image_of = [&](Index t, double x, double y) {
    const Evaluation<2> e = evaluate(map, SurfacePoint<2>{t, LocalPoint<2>(x, y)}, locator);
    if (!e.in_domain)
      throw Error(fmt::format("refine: the point ({}, {}) of S1 element {} is outside the map's domain; refinement "
                              "through a map needs a parametrization",
                              x, y, t));
    return e.world;
  };

  std::vector<Index> lattice((n + 1) * (n + 1));
  const auto s1_elements = static_cast<std::uint64_t>(s1.element_count());
  for (Index t = 0; t < s1.element_count(); ++t) {
    if (t % progress_every == 0) report_progress(options.progress, "refining S1 elements", static_cast<std::uint64_t>(t), s1_elements);
    const auto& c = s1.element(t);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        // (i, j): local coordinates (i/n, j/n), i along corner 0 -> 1, j along corner 0 -> 2.
        std::tuple<int, Index, int> key{2, t, i * (n + 1) + j};
        auto on_edge = [&](Index a, Index b, int steps_from_a) {
          const Index e = s1.find_edge(a, b);
          return std::tuple<int, Index, int>{1, e, a < b ? steps_from_a : n - steps_from_a};
        };
        if (i == 0 && j == 0) key = {0, c[0], 0};
        else if (i == n) key = {0, c[1], 0};
        else if (j == n) key = {0, c[2], 0};
        else if (j == 0) key = on_edge(c[0], c[1], i);
        else if (i == 0) key = on_edge(c[0], c[2], j);
        else if (i + j == n) key = on_edge(c[1], c[2], j);
        Index id;
        if (std::get<0>(key) == 2) {
          id = static_cast<Index>(vertices.size());
          vertices.push_back(image_of(t, double(i) / n, double(j) / n));
        } else if (auto it = shared.find(key); it != shared.end()) {
          id = it->second;
        } else {
          id = static_cast<Index>(vertices.size());
          vertices.push_back(image_of(t, double(i) / n, double(j) / n));
          shared.emplace(key, id);
        }
        lattice[i * (n + 1) + j] = id;
      }
    auto at = [&](int i, int j) { return lattice[i * (n + 1) + j]; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        elements.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) elements.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }

  report_progress(options.progress, "refining S1 elements", s1_elements, s1_elements);
  RefineResult result{Surface<2>(std::move(vertices), std::move(elements)), {}};
  RefineReport& r = result.report;
  r.levels = options.levels;
  r.vertices = result.surface.vertex_count();
  r.elements = result.surface.element_count();

  std::vector<CgalTriangle> triangles;
  triangles.reserve(s2.element_count());
  auto point = [](const Eigen::Vector3d& x) { return Kernel::Point_3(x(0), x(1), x(2)); };
  for (Index t = 0; t < s2.element_count(); ++t)
    triangles.emplace_back(point(s2.corner(t, 0)), point(s2.corner(t, 1)), point(s2.corner(t, 2)));
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  double sum = 0.0;
  std::size_t samples = 0;
  const Surface<2>& refined = result.surface;
  const auto refined_elements = static_cast<std::uint64_t>(refined.element_count());
  for (Index t = 0; t < refined.element_count(); ++t) {
    if (t % progress_every == 0) report_progress(options.progress, "distance to S2", static_cast<std::uint64_t>(t), refined_elements);
    const Eigen::Vector3d a = refined.corner(t, 0), b = refined.corner(t, 1), c = refined.corner(t, 2);
    for (const Eigen::Vector3d& x : {Eigen::Vector3d((a + b + c) / 3.0), Eigen::Vector3d((a + b) / 2.0),
                                     Eigen::Vector3d((b + c) / 2.0), Eigen::Vector3d((c + a) / 2.0)}) {
      const double distance = std::sqrt(CGAL::to_double(tree.squared_distance(point(x))));
      r.distance_max = std::max(r.distance_max, distance);
      sum += distance;
      ++samples;
    }
  }
  report_progress(options.progress, "distance to S2", refined_elements, refined_elements);
  r.distance_mean = samples > 0 ? sum / samples : 0.0;
  const double diagonal = (s2.bounding_box_max() - s2.bounding_box_min()).norm();
  r.distance_max_relative = diagonal > 0.0 ? r.distance_max / diagonal : 0.0;
  r.refined_quality = aspect_ratio_summary(refined);
  r.coarse_quality = aspect_ratio_summary(s1);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace plmap
