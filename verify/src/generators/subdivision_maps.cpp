// The subdivision maps of subdivision_maps.hpp and their sample input surfaces.

#include <plmap/core/map_builder.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace plmap::generators {
std::shared_ptr<const Surface<2>> two_triangles() {
  std::vector<WorldPoint<2>> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  return std::make_shared<const Surface<2>>(std::move(v),
                                            std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}});
}

std::shared_ptr<const Surface<2>> bumpy_grid(int n) {
  std::vector<WorldPoint<2>> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      v.push_back({x, y, 0.1 * std::sin(3 * x) * std::cos(2 * y)});
    }
  std::vector<ElementCorners<2>> t;
  auto id = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(t));
}

std::shared_ptr<const Surface<1>> zigzag_curve(int n) {
  std::vector<WorldPoint<1>> v;
  for (int i = 0; i <= n; ++i) v.push_back({double(i), 0.3 * (i % 2)});
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i < n; ++i) e.push_back({Index(i), Index(i + 1)});
  return std::make_shared<const Surface<1>>(std::move(v), std::move(e));
}

SubdivisionMap<2> subdivision_map(std::shared_ptr<const Surface<2>> s1, int k, double jitter, std::uint64_t seed,
                                  const DropRule& drop) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> shake(-jitter / k, jitter / k);
  enum class Where { vertex, edge, inside };
  struct Point {
    Where where;
    Index element;  // an element containing the point, for the world position
    LocalPoint<2> local;
    Index vertex_or_edge;
    double edge_t;
  };
  std::vector<Point> points;
  std::map<std::tuple<int, Index, int>, Index> shared;  // (kind, vertex/edge, step) -> point
  std::vector<ElementCorners<2>> sub;                   // sub-triangles as point indices
  std::vector<std::pair<Index, LocalPoint<2>>> sub_centroid;
  std::vector<int> sub_number;
  for (Index t = 0; t < s1->element_count(); ++t) {
    // grid[i][j]: point with local coordinates (i/k, j/k), i + j <= k
    std::vector<std::vector<Index>> grid(k + 1, std::vector<Index>(k + 1, invalid_index));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const LocalPoint<2> xi(double(i) / k, double(j) / k);
        int corner = -1, edge = -1, step = 0;  // step along the local edge from its first corner
        if (i == 0 && j == 0) corner = 0;
        else if (i == k) corner = 1;
        else if (j == k) corner = 2;
        else if (j == 0) edge = 0, step = i;
        else if (i + j == k) edge = 1, step = j;
        else if (i == 0) edge = 2, step = k - j;
        if (corner >= 0) {
          const Index v = s1->element(t)[corner];
          auto [it, fresh] = shared.try_emplace({0, v, 0}, Index(points.size()));
          if (fresh) points.push_back({Where::vertex, t, xi, v, 0.0});
          grid[i][j] = it->second;
        } else if (edge >= 0) {
          const Index e = s1->element_edge(t, edge);
          const bool forward = s1->local_edge_is_forward(t, edge);
          const int m = forward ? step : k - step;  // steps from the smaller-index vertex
          auto [it, fresh] = shared.try_emplace({1, e, m}, Index(points.size()));
          if (fresh) points.push_back({Where::edge, t, xi, e, double(m) / k});
          grid[i][j] = it->second;
        } else {
          LocalPoint<2> moved = xi;
          if (jitter > 0) moved += LocalPoint<2>(shake(rng), shake(rng));
          grid[i][j] = Index(points.size());
          points.push_back({Where::inside, t, moved, invalid_index, 0.0});
        }
      }
    // Position on this element of grid point (i, j): shared corner and edge points are stored
    // with the local coordinates of the element that created them, so take the grid value.
    auto local_here = [&](int i, int j) {
      const Index p = grid[i][j];
      return points[p].where == Where::inside ? points[p].local
                                              : LocalPoint<2>(double(i) / k, double(j) / k);
    };
    int number = 0;
    auto add = [&](std::array<int, 2> a, std::array<int, 2> b, std::array<int, 2> c) {
      sub.push_back({grid[a[0]][a[1]], grid[b[0]][b[1]], grid[c[0]][c[1]]});
      sub_number.push_back(number++);
      sub_centroid.push_back(
          {t, (local_here(a[0], a[1]) + local_here(b[0], b[1]) + local_here(c[0], c[1])) / 3.0});
    };
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        add({i, j}, {i + 1, j}, {i, j + 1});
        if (i + j + 1 < k) add({i + 1, j}, {i + 1, j + 1}, {i, j + 1});
      }
  }
  // Keep the sub-triangles that survive the drop rule; S2 holds only the points they use.
  SubdivisionMap<2> out;
  out.domain = s1;
  std::vector<Index> target_vertex(points.size(), invalid_index);
  std::vector<WorldPoint<2>> vertices;
  std::vector<ElementCorners<2>> elements;
  for (std::size_t s = 0; s < sub.size(); ++s) {
    if (drop && drop(sub_centroid[s].first, sub_number[s])) {
      out.holes.push_back({sub_centroid[s].first, sub_centroid[s].second});
      continue;
    }
    ElementCorners<2> c;
    for (int q = 0; q < 3; ++q) {
      Index& v = target_vertex[sub[s][q]];
      if (v == invalid_index) {
        v = Index(vertices.size());
        const Point& p = points[sub[s][q]];
        WorldPoint<2> x = s1->world_position(p.element, p.local);
        x(2) += 0.05 * std::sin(7 * x(0) + 3 * x(1));  // S2 is not S1: a wavy copy
        vertices.push_back(x);
      }
      c[q] = v;
    }
    elements.push_back(c);
  }
  out.target = std::make_shared<const Surface<2>>(std::move(vertices), std::move(elements));
  MapBuilder<2> builder(s1, out.target);
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Index v = target_vertex[p];
    if (v == invalid_index) continue;
    switch (points[p].where) {
      case Where::vertex: builder.add_vertex_preimage_at_vertex(v, points[p].vertex_or_edge); break;
      case Where::edge:
        builder.add_vertex_preimage_on_edge(v, points[p].vertex_or_edge, points[p].edge_t);
        break;
      case Where::inside: builder.add_vertex_preimage(v, {points[p].element, points[p].local}); break;
    }
  }
  for (Index e = 0; e < out.target->element_count(); ++e) builder.add_target_element(e);
  out.map = std::make_shared<const PlMap<2>>(std::move(builder).finalize());
  return out;
}

SubdivisionMap<1> subdivision_map(std::shared_ptr<const Surface<1>> s1, int k, double jitter, std::uint64_t seed,
                                  const DropRule& drop) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> shake(-jitter / k, jitter / k);
  struct Point {
    Index element;
    double s;
    Index vertex;  // S1 vertex, or invalid for interior points
  };
  std::vector<Point> points;
  std::map<Index, Index> at_vertex;
  std::vector<std::array<Index, 2>> sub;
  std::vector<std::pair<Index, double>> sub_centre;
  std::vector<int> sub_number;
  for (Index t = 0; t < s1->element_count(); ++t) {
    std::vector<Index> row(k + 1);
    std::vector<double> pos(k + 1);
    for (int i = 0; i <= k; ++i) {
      pos[i] = double(i) / k;
      if (i == 0 || i == k) {
        const Index v = s1->element(t)[i == 0 ? 0 : 1];
        auto [it, fresh] = at_vertex.try_emplace(v, Index(points.size()));
        if (fresh) points.push_back({t, pos[i], v});
        row[i] = it->second;
      } else {
        if (jitter > 0) pos[i] += shake(rng);
        row[i] = Index(points.size());
        points.push_back({t, pos[i], invalid_index});
      }
    }
    for (int i = 0; i < k; ++i) {
      sub.push_back({row[i], row[i + 1]});
      sub_centre.push_back({t, 0.5 * (pos[i] + pos[i + 1])});
      sub_number.push_back(i);
    }
  }
  SubdivisionMap<1> out;
  out.domain = s1;
  std::vector<Index> target_vertex(points.size(), invalid_index);
  std::vector<WorldPoint<1>> vertices;
  std::vector<ElementCorners<1>> elements;
  for (std::size_t s = 0; s < sub.size(); ++s) {
    if (drop && drop(sub_centre[s].first, sub_number[s])) {
      out.holes.push_back({sub_centre[s].first, LocalPoint<1>(sub_centre[s].second)});
      continue;
    }
    ElementCorners<1> c;
    for (int q = 0; q < 2; ++q) {
      Index& v = target_vertex[sub[s][q]];
      if (v == invalid_index) {
        v = Index(vertices.size());
        const Point& p = points[sub[s][q]];
        WorldPoint<1> x = s1->world_position(p.element, LocalPoint<1>(p.s));
        x(1) += 0.05 * std::sin(5 * x(0));
        vertices.push_back(x);
      }
      c[q] = v;
    }
    elements.push_back(c);
  }
  out.target = std::make_shared<const Surface<1>>(std::move(vertices), std::move(elements));
  MapBuilder<1> builder(s1, out.target);
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Index v = target_vertex[p];
    if (v == invalid_index) continue;
    if (points[p].vertex != invalid_index)
      builder.add_vertex_preimage_at_vertex(v, points[p].vertex);
    else
      builder.add_vertex_preimage(v, {points[p].element, LocalPoint<1>(points[p].s)});
  }
  for (Index e = 0; e < out.target->element_count(); ++e) builder.add_target_element(e);
  out.map = std::make_shared<const PlMap<1>>(std::move(builder).finalize());
  return out;
}

}  // namespace plmap::generators
