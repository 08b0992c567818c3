// Identity and refinement maps (see random_maps.hpp); the overlays are in overlay_maps.cpp.

#include <plmap/verify/generators/random_maps.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <stdexcept>

namespace plmap::generators {

template <int d>
void add_vertex_preimage(MapBuilder<d>& builder, Index target_vertex, const DomainLocation<d>& where) {
  using Kind = typename DomainLocation<d>::Kind;
  switch (where.kind) {
    case Kind::isolated: return;  // an isolated S2 vertex needs no preimage
    case Kind::vertex: builder.add_vertex_preimage_at_vertex(target_vertex, where.index); return;
    case Kind::edge:
      if constexpr (d == 2) {
        builder.add_vertex_preimage_on_edge(target_vertex, where.index, where.edge_parameter);
        return;
      }
      break;
    case Kind::element: builder.add_vertex_preimage(target_vertex, where.point); return;
  }
  throw std::logic_error("add_vertex_preimage: edge location on a curve");
}

template void add_vertex_preimage(MapBuilder<1>&, Index, const DomainLocation<1>&);
template void add_vertex_preimage(MapBuilder<2>&, Index, const DomainLocation<2>&);

// ---- identity ------------------------------------------------------------------------------------

template <int d>
MapCase<d> identity_map(std::shared_ptr<const Surface<d>> surface, std::string description) {
  MapBuilder<d> builder(surface, surface);
  MapCase<d> c;
  c.description = std::move(description);
  for (Index v = 0; v < surface->vertex_count(); ++v) {
    if (surface->vertex_elements(v).empty()) {  // isolated: not part of the surface
      c.target_vertex_preimage.push_back(no_preimage<d>());
      continue;
    }
    builder.add_vertex_preimage_at_vertex(v, v);
    const Index t = surface->vertex_elements(v).front();
    c.target_vertex_preimage.push_back({t, reference_corner<d>(surface->local_corner(t, v))});
  }
  for (Index t = 0; t < surface->element_count(); ++t) builder.add_target_element(t);
  c.map = std::make_shared<const PlMap<d>>(std::move(builder).finalize());
  c.domain = surface;
  c.target = std::move(surface);
  return c;
}

template MapCase<1> identity_map(std::shared_ptr<const Surface<1>>, std::string);
template MapCase<2> identity_map(std::shared_ptr<const Surface<2>>, std::string);

// ---- refinement ----------------------------------------------------------------------------------

namespace {

/// Up to `max_count` distinct parameters m/64 in [4/64, 60/64], at least 4/64 apart, sorted.
/// Dyadic, so 1 - t is exact and a point (1 - t, t) lies exactly on the line x + y = 1.
std::vector<double> dyadic_parameters(int max_count, Rng& rng) {
  const int count = uniform_index(rng, max_count + 1);
  std::vector<int> chosen;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(chosen.size()) < count; ++attempt) {
    const int m = 4 + uniform_index(rng, 57);
    if (std::all_of(chosen.begin(), chosen.end(), [m](int c) { return std::abs(c - m) >= 4; }))
      chosen.push_back(m);
  }
  std::sort(chosen.begin(), chosen.end());
  std::vector<double> t;
  for (int m : chosen) t.push_back(m / 64.0);
  return t;
}

/// Local coordinates of the point at parameter u along local edge k (from corner k to k+1).
LocalPoint<2> local_on_edge(int k, double u) {
  switch (k) {
    case 0: return {u, 0.0};
    case 1: return {1.0 - u, u};
    default: return {0.0, 1.0 - u};
  }
}

/// Where each vertex of S1 lies in S1 itself: at its corner of its first element, or nowhere
/// for an isolated vertex (which stays an isolated vertex of the refinement).
template <int d>
std::vector<DomainLocation<d>> locations_of_vertices(const Surface<d>& s1) {
  std::vector<DomainLocation<d>> out;
  out.reserve(static_cast<std::size_t>(s1.vertex_count()));
  for (Index v = 0; v < s1.vertex_count(); ++v) {
    DomainLocation<d> loc;
    loc.kind = DomainLocation<d>::Kind::vertex;
    loc.index = v;
    if (s1.vertex_elements(v).empty()) {
      loc.kind = DomainLocation<d>::Kind::isolated;
      loc.point = no_preimage<d>();
    } else {
      const Index t = s1.vertex_elements(v).front();
      loc.point = {t, reference_corner<d>(s1.local_corner(t, v))};
    }
    out.push_back(loc);
  }
  return out;
}

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

Refinement<2> refine_triangles(const Surface<2>& s1, const RefinementOptions& options, Rng& rng) {
  Refinement<2> out;
  std::vector<WorldPoint<2>> vertices = s1.vertices();
  out.vertex_location = locations_of_vertices(s1);

  // Points on edges: created once per S1 edge, so all triangles of the edge share them.
  std::vector<std::vector<double>> edge_parameters(s1.edge_count());
  std::vector<Index> edge_first_vertex(s1.edge_count());
  for (Index e = 0; e < s1.edge_count(); ++e) {
    edge_parameters[e] = dyadic_parameters(options.max_points_per_edge, rng);
    edge_first_vertex[e] = static_cast<Index>(vertices.size());
    const auto [a, b] = s1.edge_vertices(e);
    const EdgeIncidence inc = s1.edge_elements(e).front();
    const bool forward = s1.local_edge_is_forward(inc.element, inc.local_edge);
    for (double t : edge_parameters[e]) {
      vertices.push_back((1.0 - t) * s1.vertex(a) + t * s1.vertex(b));
      DomainLocation<2> loc;
      loc.kind = DomainLocation<2>::Kind::edge;
      loc.index = e;
      loc.edge_parameter = t;
      loc.point = {inc.element, local_on_edge(inc.local_edge, forward ? t : 1.0 - t)};
      out.vertex_location.push_back(loc);
    }
  }

  std::vector<ElementCorners<2>> elements;
  for (Index t = 0; t < s1.element_count(); ++t) {
    std::vector<std::pair<LocalPoint<2>, Index>> points;
    for (int k = 0; k < 3; ++k) points.push_back({reference_corner<2>(k), s1.element(t)[k]});
    for (int k = 0; k < 3; ++k) {
      const Index e = s1.element_edge(t, k);
      const bool forward = s1.local_edge_is_forward(t, k);
      for (std::size_t i = 0; i < edge_parameters[e].size(); ++i) {
        const double u = forward ? edge_parameters[e][i] : 1.0 - edge_parameters[e][i];
        points.push_back({local_on_edge(k, u), edge_first_vertex[e] + static_cast<Index>(i)});
      }
    }
    // Interior points away from the edges and from each other (no slivers).
    const int count = uniform_index(rng, options.max_points_per_element + 1);
    std::vector<LocalPoint<2>> interior;
    for (int attempt = 0; attempt < 30 * count && static_cast<int>(interior.size()) < count; ++attempt) {
      const LocalPoint<2> xi{uniform_unit(rng), uniform_unit(rng)};
      if (std::min({xi.x(), xi.y(), 1.0 - xi.x() - xi.y()}) < 0.1) continue;
      if (std::any_of(interior.begin(), interior.end(),
                      [&](const LocalPoint<2>& q) { return (q - xi).norm() < 0.1; }))
        continue;
      interior.push_back(xi);
    }
    for (const auto& xi : interior) {
      const auto v = static_cast<Index>(vertices.size());
      vertices.push_back(s1.world_position(t, xi));
      DomainLocation<2> loc;
      loc.kind = DomainLocation<2>::Kind::element;
      loc.index = t;
      loc.point = {t, xi};
      out.vertex_location.push_back(loc);
      points.push_back({xi, v});
    }

    // The local frame is counter-clockwise for the element, so CGAL's ccw faces keep its
    // orientation.
    Delaunay dt;
    for (const auto& [xi, v] : points) dt.insert(Kernel::Point_2(xi.x(), xi.y()))->info() = v;
    std::vector<ElementCorners<2>> local_elements;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      local_elements.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    std::sort(local_elements.begin(), local_elements.end());
    elements.insert(elements.end(), local_elements.begin(), local_elements.end());
  }
  out.refined = Surface<2>(std::move(vertices), std::move(elements));
  return out;
}

Refinement<1> refine_segments(const Surface<1>& s1, const RefinementOptions& options, Rng& rng) {
  Refinement<1> out;
  std::vector<WorldPoint<1>> vertices = s1.vertices();
  out.vertex_location = locations_of_vertices(s1);
  std::vector<ElementCorners<1>> elements;
  for (Index t = 0; t < s1.element_count(); ++t) {
    Index previous = s1.element(t)[0];
    for (double u : dyadic_parameters(options.max_points_per_element, rng)) {
      const auto v = static_cast<Index>(vertices.size());
      vertices.push_back(s1.world_position(t, LocalPoint<1>(u)));
      DomainLocation<1> loc;
      loc.kind = DomainLocation<1>::Kind::element;
      loc.index = t;
      loc.point = {t, LocalPoint<1>(u)};
      out.vertex_location.push_back(loc);
      elements.push_back({previous, v});
      previous = v;
    }
    elements.push_back({previous, s1.element(t)[1]});
  }
  out.refined = Surface<1>(std::move(vertices), std::move(elements));
  return out;
}

}  // namespace

template <int d>
Refinement<d> random_refinement(const Surface<d>& s1, const RefinementOptions& options, Rng& rng) {
  if (options.max_points_per_edge < 0 || options.max_points_per_element < 0)
    throw std::invalid_argument("random_refinement: negative point count");
  if constexpr (d == 2)
    return refine_triangles(s1, options, rng);
  else
    return refine_segments(s1, options, rng);
}

template Refinement<1> random_refinement(const Surface<1>&, const RefinementOptions&, Rng&);
template Refinement<2> random_refinement(const Surface<2>&, const RefinementOptions&, Rng&);

template <int d>
MapCase<d> refinement_map(std::shared_ptr<const Surface<d>> s1, const Refinement<d>& refinement,
                          std::string description) {
  auto s2 = std::make_shared<const Surface<d>>(refinement.refined);
  MapBuilder<d> builder(s1, s2);
  MapCase<d> c;
  c.description = std::move(description);
  for (Index v = 0; v < s2->vertex_count(); ++v) {
    add_vertex_preimage(builder, v, refinement.vertex_location[v]);
    c.target_vertex_preimage.push_back(refinement.vertex_location[v].point);
  }
  for (Index t = 0; t < s2->element_count(); ++t) builder.add_target_element(t);
  c.map = std::make_shared<const PlMap<d>>(std::move(builder).finalize());
  c.domain = std::move(s1);
  c.target = std::move(s2);
  return c;
}

template MapCase<1> refinement_map(std::shared_ptr<const Surface<1>>, const Refinement<1>&, std::string);
template MapCase<2> refinement_map(std::shared_ptr<const Surface<2>>, const Refinement<2>&, std::string);

}  // namespace plmap::generators
