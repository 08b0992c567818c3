// Random surfaces for tests and examples (see random_surfaces.hpp).

#include <plmap/verify/generators/random_surfaces.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plmap::generators {

double uniform_unit(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

double uniform_real(Rng& rng, double lo, double hi) { return lo + (hi - lo) * uniform_unit(rng); }

int uniform_index(Rng& rng, int n) {
  if (n <= 0) throw std::invalid_argument("uniform_index: empty range");
  return static_cast<int>(rng() % static_cast<std::uint64_t>(n));
}

namespace {

/// Drops vertices no element uses (e.g. inside a hole) and renumbers the elements.
template <int d>
Surface<d> compact_surface(const std::vector<WorldPoint<d>>& vertices,
                           std::vector<ElementCorners<d>> elements) {
  std::vector<Index> new_index(vertices.size(), invalid_index);
  std::vector<WorldPoint<d>> kept;
  for (auto& e : elements)
    for (auto& v : e) {
      if (new_index[v] == invalid_index) {
        new_index[v] = static_cast<Index>(kept.size());
        kept.push_back(vertices[v]);
      }
      v = new_index[v];
    }
  return Surface<d>(std::move(kept), std::move(elements));
}

bool on_hole_boundary(double x, double y) {
  const bool in_x = x >= HoleBox::x0 && x <= HoleBox::x1;
  const bool in_y = y >= HoleBox::y0 && y <= HoleBox::y1;
  return (in_x && (y == HoleBox::y0 || y == HoleBox::y1)) ||
         (in_y && (x == HoleBox::x0 || x == HoleBox::x1));
}

}  // namespace

// ---- grid --------------------------------------------------------------------------------------

Surface<2> grid_triangulation(const GridOptions& options, Rng& rng) {
  const int n = options.cells;
  if (n < 1) throw std::invalid_argument("grid_triangulation: need at least one cell");
  if (options.with_hole && n % 4 != 0)
    throw std::invalid_argument("grid_triangulation: with_hole needs a multiple of 4 cells");
  if (!(options.jitter >= 0.0 && options.jitter <= 0.2))
    throw std::invalid_argument("grid_triangulation: jitter must be in [0, 0.2]");

  const double h = 1.0 / n;
  std::vector<WorldPoint<2>> vertices;
  vertices.reserve(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      // i / n rather than i * h: exact whenever n is a power of two.
      double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      // Draw both numbers for every vertex so the sequence does not depend on the options.
      const double dx = options.jitter * h * uniform_real(rng, -1.0, 1.0);
      const double dy = options.jitter * h * uniform_real(rng, -1.0, 1.0);
      const bool side_x = (i == 0 || i == n), side_y = (j == 0 || j == n);
      const bool fixed = (side_x && side_y) || (options.with_hole && on_hole_boundary(x, y));
      if (!fixed) {
        if (!side_x) x += dx;  // vertices on a vertical side only slide along it
        if (!side_y) y += dy;
      }
      vertices.push_back({x, y, 0.0});
    }

  auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  std::vector<ElementCorners<2>> elements;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool main_diagonal = (rng() & 1u) != 0;
      const double cx = (i + 0.5) / n, cy = (j + 0.5) / n;
      if (options.with_hole && HoleBox::contains_strictly(cx, cy)) continue;
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
      if (main_diagonal) {
        elements.push_back({a, b, c});
        elements.push_back({a, c, e});
      } else {
        elements.push_back({a, b, e});
        elements.push_back({b, c, e});
      }
    }
  return compact_surface<2>(vertices, std::move(elements));
}

// ---- constrained Delaunay ------------------------------------------------------------------------

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

struct Side {
  Eigen::Vector2d from, to;  // axis-parallel
  bool contains(const Eigen::Vector2d& p) const {
    if (from.x() == to.x())
      return p.x() == from.x() && p.y() >= std::min(from.y(), to.y()) &&
             p.y() <= std::max(from.y(), to.y());
    return p.y() == from.y() && p.x() >= std::min(from.x(), to.x()) &&
           p.x() <= std::max(from.x(), to.x());
  }
  Eigen::Vector2d at(double t) const {
    // Keep the fixed coordinate exact.
    Eigen::Vector2d p = from + t * (to - from);
    if (from.x() == to.x()) p.x() = from.x();
    else p.y() = from.y();
    return p;
  }
};

double distance_to_box(const Eigen::Vector2d& p) {
  const double dx = std::max({HoleBox::x0 - p.x(), 0.0, p.x() - HoleBox::x1});
  const double dy = std::max({HoleBox::y0 - p.y(), 0.0, p.y() - HoleBox::y1});
  return std::hypot(dx, dy);
}

}  // namespace

Surface<2> delaunay_triangulation(const DelaunayOptions& options, Rng& rng) {
  if (options.interior_points < 0 || options.boundary_points < 0 || options.grid_points < 0)
    throw std::invalid_argument("delaunay_triangulation: negative point count");

  std::vector<Side> sides = {{{0, 0}, {1, 0}}, {{1, 0}, {1, 1}}, {{1, 1}, {0, 1}}, {{0, 1}, {0, 0}}};
  if (options.with_hole) {
    const Eigen::Vector2d a{HoleBox::x0, HoleBox::y0}, b{HoleBox::x1, HoleBox::y0},
        c{HoleBox::x1, HoleBox::y1}, e{HoleBox::x0, HoleBox::y1};
    sides.push_back({a, b});
    sides.push_back({b, c});
    sides.push_back({c, e});
    sides.push_back({e, a});
  }

  std::vector<Eigen::Vector2d> points;
  for (const auto& s : sides) points.push_back(s.from);  // corners of square and hole

  const int total = 8 + options.interior_points + options.boundary_points + options.grid_points;
  // Minimum separation: about half the spacing of a uniform distribution of all points.
  const double separation = 0.4 / std::sqrt(static_cast<double>(total));
  auto far_from_points = [&](const Eigen::Vector2d& p, double sep) {
    return std::all_of(points.begin(), points.end(),
                       [&](const Eigen::Vector2d& q) { return (p - q).norm() >= sep; });
  };
  auto far_from_boundary = [&](const Eigen::Vector2d& p) {
    if (std::min({p.x(), p.y(), 1.0 - p.x(), 1.0 - p.y()}) < separation) return false;
    return !options.with_hole || distance_to_box(p) >= separation;
  };

  // Grid points first: exact dyadic coordinates, possibly on the boundary.
  for (int k = 0, attempts = 0; k < options.grid_points && attempts < 20 * options.grid_points + 20;
       ++attempts) {
    const Eigen::Vector2d p{uniform_index(rng, 9) / 8.0, uniform_index(rng, 9) / 8.0};
    if (options.with_hole && HoleBox::contains_strictly(p.x(), p.y())) continue;
    if (!far_from_points(p, 0.1)) continue;  // also rejects duplicates
    points.push_back(p);
    ++k;
  }
  for (int k = 0, attempts = 0;
       k < options.boundary_points && attempts < 20 * options.boundary_points + 20; ++attempts) {
    const Side& s = sides[uniform_index(rng, static_cast<int>(sides.size()))];
    const Eigen::Vector2d p = s.at(uniform_real(rng, 0.05, 0.95));
    if (!far_from_points(p, separation)) continue;
    points.push_back(p);
    ++k;
  }
  for (int k = 0, attempts = 0;
       k < options.interior_points && attempts < 50 * options.interior_points + 50; ++attempts) {
    const Eigen::Vector2d p{uniform_unit(rng), uniform_unit(rng)};
    if (options.with_hole && distance_to_box(p) == 0.0) continue;
    if (!far_from_boundary(p) || !far_from_points(p, separation)) continue;
    points.push_back(p);
    ++k;
  }

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto vh = cdt.insert(Kernel::Point_2(points[i].x(), points[i].y()));
    vh->info() = static_cast<Index>(i);
    handles.push_back(vh);
  }
  // The domain boundary as constraints between consecutive points on each side.
  for (const auto& s : sides) {
    std::vector<std::pair<double, std::size_t>> on_side;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (s.contains(points[i])) on_side.push_back({(points[i] - s.from).norm(), i});
    std::sort(on_side.begin(), on_side.end());
    for (std::size_t k = 0; k + 1 < on_side.size(); ++k)
      cdt.insert_constraint(handles[on_side[k].second], handles[on_side[k + 1].second]);
  }

  std::vector<WorldPoint<2>> vertices;
  for (const auto& p : points) vertices.push_back({p.x(), p.y(), 0.0});
  std::vector<ElementCorners<2>> elements;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const Eigen::Vector2d centroid =
        (points[f->vertex(0)->info()] + points[f->vertex(1)->info()] + points[f->vertex(2)->info()]) /
        3.0;
    if (options.with_hole && HoleBox::contains_strictly(centroid.x(), centroid.y())) continue;
    elements.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  // Sort the elements so the numbering does not depend on CGAL's face iteration order.
  std::sort(elements.begin(), elements.end());
  return compact_surface<2>(vertices, std::move(elements));
}

// ---- height field, fins, shared corner -------------------------------------------------------------

double HeightField::operator()(double x, double y) const {
  return amplitude * std::sin(kx * x + px) * std::cos(ky * y + py);
}

HeightField random_height_field(Rng& rng) {
  HeightField h;
  h.amplitude = uniform_real(rng, 0.05, 0.3);
  h.kx = uniform_real(rng, 1.0, 4.0);
  h.ky = uniform_real(rng, 1.0, 4.0);
  h.px = uniform_real(rng, 0.0, 2.0 * std::numbers::pi);
  h.py = uniform_real(rng, 0.0, 2.0 * std::numbers::pi);
  return h;
}

Surface<2> lift_to_height_field(const Surface<2>& planar, const HeightField& h) {
  std::vector<WorldPoint<2>> vertices = planar.vertices();
  for (auto& v : vertices) v.z() = h(v.x(), v.y());
  return Surface<2>(std::move(vertices), planar.elements());
}

Surface<2> add_fins(const Surface<2>& sheet, int fins, Rng& rng) {
  std::vector<Index> interior_edges;
  for (Index e = 0; e < sheet.edge_count(); ++e)
    if (sheet.edge_elements(e).size() == 2) interior_edges.push_back(e);
  if (fins < 0 || fins > static_cast<int>(interior_edges.size()))
    throw std::invalid_argument("add_fins: not enough interior edges for " + std::to_string(fins) +
                                " fins");
  std::vector<WorldPoint<2>> vertices = sheet.vertices();
  std::vector<ElementCorners<2>> elements = sheet.elements();
  for (int k = 0; k < fins; ++k) {
    // Partial Fisher-Yates: pick a not yet used edge.
    const int pick = k + uniform_index(rng, static_cast<int>(interior_edges.size()) - k);
    std::swap(interior_edges[k], interior_edges[pick]);
    const auto [a, b] = sheet.edge_vertices(interior_edges[k]);
    const WorldPoint<2> pa = sheet.vertex(a), pb = sheet.vertex(b);
    // Vertical fin above the edge: it meets the sheet only along the edge.
    WorldPoint<2> apex = 0.5 * (pa + pb);
    apex.z() += (pb - pa).norm() * uniform_real(rng, 0.5, 1.0);
    vertices.push_back(apex);
    elements.push_back({a, b, static_cast<Index>(vertices.size() - 1)});
  }
  return Surface<2>(std::move(vertices), std::move(elements));
}

Surface<2> join_at_corner(const Surface<2>& first, const Surface<2>& second) {
  auto find = [](const Surface<2>& s, double x, double y, const char* which) {
    for (Index v = 0; v < s.vertex_count(); ++v)
      if (s.vertex(v).x() == x && s.vertex(v).y() == y) return v;
    throw std::invalid_argument(std::string("join_at_corner: ") + which + " has no vertex at (" +
                                std::to_string(x) + ", " + std::to_string(y) + ")");
  };
  const Index corner_first = find(first, 1.0, 1.0, "first");
  const Index corner_second = find(second, 0.0, 0.0, "second");
  const WorldPoint<2> anchor = first.vertex(corner_first);
  const double z0 = second.vertex(corner_second).z();

  std::vector<WorldPoint<2>> vertices = first.vertices();
  std::vector<Index> renumber(second.vertex_count());
  for (Index v = 0; v < second.vertex_count(); ++v) {
    if (v == corner_second) {
      renumber[v] = corner_first;
      continue;
    }
    const WorldPoint<2>& p = second.vertex(v);
    renumber[v] = static_cast<Index>(vertices.size());
    vertices.push_back(anchor + WorldPoint<2>(p.x(), p.y(), 0.5 * (p.x() + p.y()) + p.z() - z0));
  }
  std::vector<ElementCorners<2>> elements = first.elements();
  for (const auto& e : second.elements()) elements.push_back({renumber[e[0]], renumber[e[1]], renumber[e[2]]});
  return Surface<2>(std::move(vertices), std::move(elements));
}

// ---- polylines -----------------------------------------------------------------------------------

Surface<1> random_open_polyline(int segments, Rng& rng) {
  if (segments < 1) throw std::invalid_argument("random_open_polyline: need a segment");
  std::vector<WorldPoint<1>> vertices;
  std::vector<ElementCorners<1>> elements;
  for (int i = 0; i <= segments; ++i) {
    const double shift = (i == 0 || i == segments) ? 0.0 : uniform_real(rng, -0.3, 0.3);
    vertices.push_back({(i + shift) / segments, uniform_real(rng, -0.3, 0.3)});
    if (i > 0) elements.push_back({i - 1, i});
  }
  return Surface<1>(std::move(vertices), std::move(elements));
}

Surface<1> random_closed_polyline(int segments, Rng& rng) {
  if (segments < 3) throw std::invalid_argument("random_closed_polyline: need three segments");
  std::vector<WorldPoint<1>> vertices;
  std::vector<ElementCorners<1>> elements;
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * std::numbers::pi * (i + uniform_real(rng, -0.3, 0.3)) / segments;
    const double radius = uniform_real(rng, 0.5, 1.0);
    vertices.push_back({radius * std::cos(angle), radius * std::sin(angle)});
    elements.push_back({i, (i + 1) % segments});
  }
  return Surface<1>(std::move(vertices), std::move(elements));
}

Surface<1> random_star_polyline(int arms, int segments_per_arm, Rng& rng) {
  if (arms < 3 || segments_per_arm < 1)
    throw std::invalid_argument("random_star_polyline: need three arms of at least one segment");
  std::vector<WorldPoint<1>> vertices{WorldPoint<1>::Zero()};
  std::vector<ElementCorners<1>> elements;
  const double sector = 2.0 * std::numbers::pi / arms;
  for (int a = 0; a < arms; ++a) {
    Index previous = 0;
    for (int k = 1; k <= segments_per_arm; ++k) {
      const double radius = (k + uniform_real(rng, -0.3, 0.3)) / segments_per_arm;
      // Stay within +-30% of the half sector around the arm's axis: arms never meet.
      const double angle = sector * (a + 0.3 * uniform_real(rng, -1.0, 1.0) * 0.5);
      vertices.push_back({radius * std::cos(angle), radius * std::sin(angle)});
      const auto current = static_cast<Index>(vertices.size() - 1);
      elements.push_back({previous, current});
      previous = current;
    }
  }
  return Surface<1>(std::move(vertices), std::move(elements));
}

}  // namespace plmap::generators
