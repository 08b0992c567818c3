#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/scaled_geometry.hpp>
#include <plmap/core/surface.hpp>

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>
#include <type_traits>

namespace plmap {

namespace {

constexpr const char* supported_scale_note =
    "plmap supports edge lengths from about 1e-150 to 1e150 (rescale the coordinates)";

// An element whose measure is below this fraction of (longest surface edge)^d is degenerate.
// Relative, so that scaling the surface never changes the verdict.
constexpr double degenerate_measure_fraction = 1e-14;

}  // namespace

template <int d>
  requires SurfaceDimension<d>
Surface<d>::Surface(std::vector<WorldPoint<d>> vertices, std::vector<ElementCorners<d>> elements)
    : vertices_(std::move(vertices)), elements_(std::move(elements)) {
  validate();
  build_adjacency();
}

template <int d>
  requires SurfaceDimension<d>
void Surface<d>::validate() const {
  const auto nv = static_cast<Index>(vertices_.size());
  if (vertices_.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()) ||
      elements_.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
    throw InvalidSurfaceError("surface too large for 32-bit indices");
  for (Index v = 0; v < nv; ++v) {
    if (!vertices_[v].allFinite())
      throw InvalidSurfaceError(fmt::format("vertex {} has a non-finite coordinate", v));
  }
  for (std::size_t t = 0; t < elements_.size(); ++t) {
    const auto& e = elements_[t];
    for (int k = 0; k <= d; ++k) {
      if (e[k] < 0 || e[k] >= nv)
        throw InvalidSurfaceError(fmt::format(
            "element {} refers to vertex {}, but the surface has {} vertices", t, e[k], nv));
      for (int j = 0; j < k; ++j)
        if (e[j] == e[k])
          throw InvalidSurfaceError(
              fmt::format("element {} uses vertex {} twice", t, e[k]));
    }
  }
}

template <int d>
  requires SurfaceDimension<d>
void Surface<d>::build_adjacency() {
  const auto nv = static_cast<Index>(vertices_.size());
  const auto nt = static_cast<Index>(elements_.size());
  // Walks and point location on a triangle surface read these arrays at random: on transparent
  // huge pages they miss the TLB far less (huge_page_allocator.hpp). The given vertices and
  // elements move onto such pages in one copy (a few MiB per million elements); the arrays built
  // here are marked before they are written.
  const auto on_huge_pages = [](auto& array) {
    using Array = std::remove_reference_t<decltype(array)>;
    if (array.size() * sizeof(typename Array::value_type) < HugePageAllocator<char>::huge_page_bytes) return;
    Array moved;
    reserve_for_writing(moved, array.size());
    moved.assign(array.begin(), array.end());
    array.swap(moved);
  };
  if constexpr (d == 2) {  // curves' arrays are smaller and read in order (see builder_nodes.hpp)
    on_huge_pages(vertices_);
    on_huge_pages(elements_);
    reserve_for_writing(vertex_element_begin_, static_cast<std::size_t>(nv) + 1);
    reserve_for_writing(vertex_element_, static_cast<std::size_t>(d + 1) * static_cast<std::size_t>(nt));
  }

  if (nv > 0) {
    box_min_ = box_max_ = vertices_[0];
    for (const auto& p : vertices_) {
      box_min_ = box_min_.cwiseMin(p);
      box_max_ = box_max_.cwiseMax(p);
    }
  }

  // vertex -> elements (CSR)
  vertex_element_begin_.assign(nv + 1, 0);
  for (const auto& e : elements_)
    for (Index v : e) ++vertex_element_begin_[v + 1];
  std::partial_sum(vertex_element_begin_.begin(), vertex_element_begin_.end(),
                   vertex_element_begin_.begin());
  vertex_element_.resize(vertex_element_begin_.back());
  {
    std::vector<Index> fill(vertex_element_begin_.begin(), vertex_element_begin_.end() - 1);
    for (Index t = 0; t < nt; ++t)
      for (Index v : elements_[t]) vertex_element_[fill[v]++] = t;
  }

  max_edge_length_ = 0.0;
  for (const auto& e : elements_)
    for (int k = 0; k <= d; ++k)
      for (int j = k + 1; j <= d; ++j) {
        const WorldPoint<d> edge = vertices_[e[k]] - vertices_[e[j]];
        if (!edge.allFinite())
          throw InvalidSurfaceError(fmt::format(
              "vertices {} and {} are too far apart for double arithmetic: {}", e[k], e[j], supported_scale_note));
        max_edge_length_ = std::max(max_edge_length_, scaled_length<d>(edge));
      }

  // Degeneracy is judged on measure / (longest surface edge)^d, formed from the scaled measure so
  // that it is the same number at every scale. Then the measure itself must be a normal double:
  // otherwise areas (info, coverage, kappa, the projection's measures) would be infinite or zero.
  measure_ = 0.0;
  for (Index t = 0; t < nt; ++t) {
    std::array<WorldPoint<d>, d + 1> c;
    for (int k = 0; k <= d; ++k) c[k] = corner(t, k);
    const auto [scaled, unit] = scaled_simplex_measure<d>(c);
    const double relative = scaled * std::pow(unit / max_edge_length_, d);
    if (!(relative > degenerate_measure_fraction))
      throw InvalidSurfaceError(fmt::format(
          "element {} is degenerate: its {} is {:g} times (longest edge of the surface)^{}", t,
          d == 1 ? "length" : "area", relative, d));
    const double m = d == 1 ? scaled * unit : scaled * unit * unit;
    if (!std::isfinite(m) || m < std::numeric_limits<double>::min())
      throw InvalidSurfaceError(fmt::format(
          "element {}: its {} ({:g} x {:g}^{}) is outside the range of doubles: {}", t,
          d == 1 ? "length" : "area", scaled, unit, d, supported_scale_note));
    measure_ += m;
  }
  if (!std::isfinite(measure_))
    throw InvalidSurfaceError(fmt::format("the total {} of the surface overflows a double: {}",
                                          d == 1 ? "length" : "area", supported_scale_note));

  if constexpr (d == 1) {
    // Duplicate segments (either orientation) share both vertices, so they are found among the
    // segments of their smaller vertex, without sorting all segments (which was a twentieth of
    // reading a curve of a million segments). Reported as a sort of the (smaller, larger vertex)
    // pairs would report them: the smallest pair, its two lowest-numbered segments (the
    // vertex -> elements lists hold the elements in increasing order).
    std::vector<std::pair<Index, Index>> around;  // (larger vertex, segment) of one smaller vertex
    for (Index a = 0; a < nv; ++a) {
      around.clear();
      for (const Index t : vertex_elements(a))
        if (std::min(elements_[t][0], elements_[t][1]) == a) around.emplace_back(std::max(elements_[t][0], elements_[t][1]), t);
      if (around.size() < 2) continue;
      std::sort(around.begin(), around.end());
      for (std::size_t i = 1; i < around.size(); ++i)
        if (around[i].first == around[i - 1].first)
          throw InvalidSurfaceError(fmt::format("elements {} and {} join the same two vertices",
                                                around[i - 1].second, around[i].second));
    }
    boundary_vertex_.assign(nv, false);
    for (Index v = 0; v < nv; ++v)
      boundary_vertex_[v] = vertex_element_begin_[v + 1] - vertex_element_begin_[v] == 1;
  } else {
    // Edges numbered in (smaller vertex, larger vertex) order, each edge's incidences in element
    // order. Built per smaller vertex from the vertex -> elements lists (which hold the elements
    // in increasing order): a few small sorts instead of one sort of 3 nt records, which was
    // the largest cost of reading a large surface.
    struct Record {
      Index b, t;
      int k;
    };
    std::vector<Record> around;
    edges_.clear();
    reserve_for_writing(edges_, 3 * static_cast<std::size_t>(nt) / 2 + 1);
    reserve_for_writing(element_edges_, static_cast<std::size_t>(nt));
    element_edges_.assign(nt, {invalid_index, invalid_index, invalid_index});
    edge_incidence_begin_.clear();
    reserve_for_writing(edge_incidence_begin_, 3 * static_cast<std::size_t>(nt) / 2 + 2);
    edge_incidence_.clear();
    reserve_for_writing(edge_incidence_, 3 * static_cast<std::size_t>(nt));
    for (Index a = 0; a < nv; ++a) {
      around.clear();
      for (const Index t : vertex_elements(a))
        for (int k = 0; k < 3; ++k) {
          const Index u = elements_[t][k], w = elements_[t][(k + 1) % 3];
          if (std::min(u, w) == a) around.push_back({std::max(u, w), t, k});
        }
      std::sort(around.begin(), around.end(),
                [](const Record& x, const Record& y) { return std::tie(x.b, x.t) < std::tie(y.b, y.t); });
      for (std::size_t i = 0; i < around.size(); ++i) {
        if (i == 0 || around[i].b != around[i - 1].b) {
          edge_incidence_begin_.push_back(static_cast<Index>(edge_incidence_.size()));
          edges_.push_back({a, around[i].b});
        }
        const auto e = static_cast<Index>(edges_.size() - 1);
        element_edges_[around[i].t][around[i].k] = e;
        edge_incidence_.push_back({around[i].t, around[i].k});
      }
    }
    edge_incidence_begin_.push_back(static_cast<Index>(edge_incidence_.size()));

    // Duplicate triangles (the same three vertices) share every edge, so they are found among
    // the elements of each edge without sorting all triangles. Reported as a sort of the sorted
    // vertex triples would report them: the smallest triple, its two lowest-numbered elements.
    std::optional<std::tuple<std::array<Index, 3>, Index, Index>> first_duplicate;
    auto third_vertex = [&](const EdgeIncidence& i) { return elements_[i.element][(i.local_edge + 2) % 3]; };
    for (Index e = 0; e < static_cast<Index>(edges_.size()); ++e) {
      const Index begin = edge_incidence_begin_[e], end = edge_incidence_begin_[e + 1];
      for (Index i = begin; i < end; ++i)
        for (Index j = i + 1; j < end; ++j) {
          if (third_vertex(edge_incidence_[i]) != third_vertex(edge_incidence_[j])) continue;
          std::array<Index, 3> triple = {edges_[e][0], edges_[e][1], third_vertex(edge_incidence_[i])};
          std::sort(triple.begin(), triple.end());
          const auto found = std::make_tuple(triple, edge_incidence_[i].element, edge_incidence_[j].element);
          if (!first_duplicate || found < *first_duplicate) first_duplicate = found;
        }
    }
    if (first_duplicate)
      throw InvalidSurfaceError(fmt::format("elements {} and {} have the same three vertices",
                                            std::get<1>(*first_duplicate), std::get<2>(*first_duplicate)));

    boundary_vertex_.assign(nv, false);
    for (Index e = 0; e < static_cast<Index>(edges_.size()); ++e)
      if (edge_incidence_begin_[e + 1] - edge_incidence_begin_[e] == 1) {
        boundary_vertex_[edges_[e][0]] = true;
        boundary_vertex_[edges_[e][1]] = true;
      }
  }
}

template <int d>
  requires SurfaceDimension<d>
Index Surface<d>::edge_count() const {
  if constexpr (d == 1)
    return element_count();
  else
    return static_cast<Index>(edges_.size());
}

template <int d>
  requires SurfaceDimension<d>
double Surface<d>::element_measure(Index t) const {
  std::array<WorldPoint<d>, d + 1> c;
  for (int k = 0; k <= d; ++k) c[k] = corner(t, k);
  return simplex_measure<d>(c);
}

template <int d>
  requires SurfaceDimension<d>
WorldPoint<d> Surface<d>::element_normal(Index t) const {
  if constexpr (d == 1) {
    const WorldPoint<1> u = corner(t, 1) - corner(t, 0);
    const double s = power_of_two_scale<1>({u});
    return WorldPoint<1>(u.y() / s, -u.x() / s).normalized();
  } else {
    // the cross product of the scaled edges, whose squares stay in range at every scale
    const WorldPoint<2> u = corner(t, 1) - corner(t, 0), v = corner(t, 2) - corner(t, 0);
    const double s = power_of_two_scale<2>({u, v});
    return (u / s).cross(v / s).normalized();
  }
}

template <int d>
  requires SurfaceDimension<d>
Index Surface<d>::find_edge(Index a, Index b) const
  requires(d == 2)
{
  if (a > b) std::swap(a, b);
  for (Index t : vertex_elements(a)) {
    for (int k = 0; k < 3; ++k) {
      const Index e = element_edges_[t][k];
      if (edges_[e][0] == a && edges_[e][1] == b) return e;
    }
  }
  return invalid_index;
}

template <int d>
  requires SurfaceDimension<d>
bool Surface<d>::is_boundary_vertex(Index v) const {
  return boundary_vertex_[v];
}

template <int d>
  requires SurfaceDimension<d>
Surface<d> Surface<d>::scaled_by_power_of_two(int exponent) const {
  Surface<d> out(*this);
  for (auto& p : out.vertices_)
    for (int i = 0; i <= d; ++i) p(i) = std::ldexp(p(i), exponent);
  for (int i = 0; i <= d; ++i) {
    out.box_min_(i) = std::ldexp(box_min_(i), exponent);
    out.box_max_(i) = std::ldexp(box_max_(i), exponent);
  }
  out.max_edge_length_ = std::ldexp(max_edge_length_, exponent);
  out.measure_ = std::ldexp(measure_, d * exponent);
  return out;
}

template class Surface<1>;
template class Surface<2>;

}  // namespace plmap
