// A surface renumbered by renaming its own arrays (surface_renumbering.hpp): what the constructor
// would build from the renumbered input, without validating it again or sorting every vertex's
// edges, on up to `threads` threads.

#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/surface_renumbering.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <vector>

namespace plmap {

namespace {

/// The inverse (old -> new) of `original` (new -> old), which must be a permutation of 0 .. n - 1.
std::vector<Index> inverse_permutation(std::span<const Index> original, Index n, const char* what) {
  if (original.size() != static_cast<std::size_t>(n))
    throw InvalidSurfaceError(
        fmt::format("renumbering: {} {} numbers given for a surface of {} {}s", original.size(), what, n, what));
  std::vector<Index> inverse(static_cast<std::size_t>(n), invalid_index);
  for (std::size_t i = 0; i < original.size(); ++i) {
    const Index old = original[i];
    if (old < 0 || old >= n || inverse[static_cast<std::size_t>(old)] != invalid_index)
      throw InvalidSurfaceError(fmt::format("renumbering: the new {} numbers are no permutation ({} {} {})", what,
                                            old < 0 || old >= n ? "out-of-range" : "repeated", what, old));
    inverse[static_cast<std::size_t>(old)] = static_cast<Index>(i);
  }
  return inverse;
}

/// Sorts the items of one vertex's or one edge's list, usually a few (about six, and two), by
/// insertion: std::sort's set-up cost more than the sorting there. Long lists (a vertex that
/// thousands of elements share) go to std::sort.
template <class T, class Less>
void sort_few(T* first, T* last, Less less) {
  if (last - first > 16) {
    std::sort(first, last, less);
    return;
  }
  for (T* i = first + (first != last); i < last; ++i)
    for (T* j = i; j > first && less(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
}

/// `array` resized to n items whose pages the threads have backed first (parallel_first_touch.hpp)
/// and, where the constructor puts them there (d = 2), marked for huge pages: fresh memory costs
/// more than filling it on the benchmark machine, and one thread touching all of it was most of
/// what the renumbered copy cost.
template <int d, class Vector>
void fresh_array(Vector& array, std::size_t n, unsigned threads) {
  if constexpr (d == 2)
    reserve_on_huge_pages(array, n);
  else
    array.reserve(n);
  populate_in_parallel(array.data(), n * sizeof(typename Vector::value_type), threads);
  array.resize(n);
}

}  // namespace

/// Surface's friend that fills a renumbered copy's arrays.
struct SurfaceRenumbering {
  template <int d>
  static Surface<d> build(const Surface<d>& s, std::span<const Index> original_element,
                          std::span<const Index> original_vertex, unsigned threads) {
    const Index nt = s.element_count(), nv = s.vertex_count();
    const std::vector<Index> new_element = inverse_permutation(original_element, nt, "element");
    const std::vector<Index> new_vertex = inverse_permutation(original_vertex, nv, "vertex");
    const auto on_threads = [threads](Index n, const auto& work) {
      parallel_ranges(static_cast<std::size_t>(n), threads, [&](std::size_t begin, std::size_t end) {
        for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) work(i);
      });
    };
    const auto old_vertex = [&](Index v) { return original_vertex[static_cast<std::size_t>(v)]; };
    const auto old_element = [&](Index t) { return original_element[static_cast<std::size_t>(t)]; };

    Surface<d> out;
    fresh_array<d>(out.vertices_, static_cast<std::size_t>(nv), threads);
    on_threads(nv, [&](Index v) { out.vertices_[v] = s.vertices_[old_vertex(v)]; });
    fresh_array<d>(out.elements_, static_cast<std::size_t>(nt), threads);
    on_threads(nt, [&](Index t) {
      ElementCorners<d> corners = s.elements_[old_element(t)];
      for (Index& v : corners) v = new_vertex[static_cast<std::size_t>(v)];
      out.elements_[t] = corners;
    });

    // minima, maxima and the longest edge do not depend on the order they are taken in
    out.box_min_ = s.box_min_;
    out.box_max_ = s.box_max_;
    out.max_edge_length_ = s.max_edge_length_;
    // a sum does: the constructor's, element after element in the new order, of the same
    // per-element measures (same corners, same order), computed on all threads
    {
      const auto measures = std::make_unique_for_overwrite<double[]>(static_cast<std::size_t>(nt));
      on_threads(nt, [&](Index t) { measures[static_cast<std::size_t>(t)] = s.element_measure(old_element(t)); });
      out.measure_ = 0.0;
      for (Index t = 0; t < nt; ++t) out.measure_ += measures[static_cast<std::size_t>(t)];
    }

    // vertex -> elements: each list renamed, then in increasing new element order
    fresh_array<d>(out.vertex_element_begin_, static_cast<std::size_t>(nv) + 1, threads);
    out.vertex_element_begin_[0] = 0;
    for (Index v = 0; v < nv; ++v)
      out.vertex_element_begin_[v + 1] =
          out.vertex_element_begin_[v] + static_cast<Index>(s.vertex_elements(old_vertex(v)).size());
    fresh_array<d>(out.vertex_element_, static_cast<std::size_t>(out.vertex_element_begin_[nv]), threads);
    on_threads(nv, [&](Index v) {
      Index* const first = out.vertex_element_.data() + out.vertex_element_begin_[v];
      Index* last = first;
      for (const Index t : s.vertex_elements(old_vertex(v))) *last++ = new_element[static_cast<std::size_t>(t)];
      sort_few(first, last, std::less<Index>());
    });

    out.boundary_vertex_.assign(static_cast<std::size_t>(nv), false);  // bits: one thread
    for (Index v = 0; v < nv; ++v) out.boundary_vertex_[static_cast<std::size_t>(v)] = s.boundary_vertex_[static_cast<std::size_t>(old_vertex(v))];

    if constexpr (d == 2) rename_edges(s, out, original_element, new_element, new_vertex, threads);
    return out;
  }

  /// The edges of `s` renumbered as the constructor numbers them on the new vertex numbers: by
  /// (smaller, larger) vertex, i.e. a counting sort by the smaller end and then each vertex's
  /// few edges by the larger; each edge's incidences renamed and in increasing new element order.
  static void rename_edges(const Surface<2>& s, Surface<2>& out, std::span<const Index> original_element,
                           const std::vector<Index>& new_element, const std::vector<Index>& new_vertex,
                           unsigned threads) {
    const auto ne = static_cast<Index>(s.edges_.size());
    const auto nv = static_cast<Index>(new_vertex.size()), nt = static_cast<Index>(new_element.size());
    const auto on_threads = [threads](Index n, const auto& work) {
      parallel_ranges(static_cast<std::size_t>(n), threads, [&](std::size_t begin, std::size_t end) {
        for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i) work(i);
      });
    };
    const auto renamed = [&](Index e) {
      const std::array<Index, 2>& ab = s.edges_[e];
      const Index a = new_vertex[static_cast<std::size_t>(ab[0])], b = new_vertex[static_cast<std::size_t>(ab[1])];
      return a < b ? std::array<Index, 2>{a, b} : std::array<Index, 2>{b, a};
    };

    // new edge -> old edge: a counting sort by the new smaller vertex (two passes of a few
    // operations per edge, on one thread), then each vertex's edges by their larger vertex
    std::vector<Index> original_edge(static_cast<std::size_t>(ne));
    {
      std::vector<Index> begin(static_cast<std::size_t>(nv) + 1, 0);
      for (Index e = 0; e < ne; ++e) ++begin[static_cast<std::size_t>(renamed(e)[0]) + 1];
      std::partial_sum(begin.begin(), begin.end(), begin.begin());
      std::vector<Index> fill(begin.begin(), begin.end() - 1);
      for (Index e = 0; e < ne; ++e) original_edge[static_cast<std::size_t>(fill[static_cast<std::size_t>(renamed(e)[0])]++)] = e;
      on_threads(nv, [&](Index a) {
        sort_few(original_edge.data() + begin[static_cast<std::size_t>(a)], original_edge.data() + begin[static_cast<std::size_t>(a) + 1],
                 [&](Index e, Index f) { return renamed(e)[1] < renamed(f)[1]; });
      });
    }
    std::vector<Index> new_edge(static_cast<std::size_t>(ne));
    on_threads(ne, [&](Index e) { new_edge[static_cast<std::size_t>(original_edge[static_cast<std::size_t>(e)])] = e; });

    fresh_array<2>(out.edges_, static_cast<std::size_t>(ne), threads);
    on_threads(ne, [&](Index e) { out.edges_[e] = renamed(original_edge[static_cast<std::size_t>(e)]); });

    fresh_array<2>(out.edge_incidence_begin_, static_cast<std::size_t>(ne) + 1, threads);
    out.edge_incidence_begin_[0] = 0;
    for (Index e = 0; e < ne; ++e) {
      const Index old = original_edge[static_cast<std::size_t>(e)];
      out.edge_incidence_begin_[e + 1] = out.edge_incidence_begin_[e] + (s.edge_incidence_begin_[old + 1] - s.edge_incidence_begin_[old]);
    }
    fresh_array<2>(out.edge_incidence_, static_cast<std::size_t>(out.edge_incidence_begin_[ne]), threads);
    // every element keeps its corners in their order, so local edge k stays local edge k
    on_threads(ne, [&](Index e) {
      EdgeIncidence* const first = out.edge_incidence_.data() + out.edge_incidence_begin_[e];
      EdgeIncidence* last = first;
      for (const EdgeIncidence& i : s.edge_elements(original_edge[static_cast<std::size_t>(e)]))
        *last++ = {new_element[static_cast<std::size_t>(i.element)], i.local_edge};
      sort_few(first, last, [](const EdgeIncidence& x, const EdgeIncidence& y) { return x.element < y.element; });
    });

    fresh_array<2>(out.element_edges_, static_cast<std::size_t>(nt), threads);
    on_threads(nt, [&](Index t) {
      const std::array<Index, 3>& old = s.element_edges_[original_element[static_cast<std::size_t>(t)]];
      for (int k = 0; k < 3; ++k) out.element_edges_[t][k] = new_edge[static_cast<std::size_t>(old[k])];
    });
  }
};

template <int d>
  requires SurfaceDimension<d>
Surface<d> renumbered_surface(const Surface<d>& s, std::span<const Index> original_element,
                              std::span<const Index> original_vertex, unsigned threads) {
  return SurfaceRenumbering::build<d>(s, original_element, original_vertex, threads);
}

template Surface<1> renumbered_surface<1>(const Surface<1>&, std::span<const Index>, std::span<const Index>, unsigned);
template Surface<2> renumbered_surface<2>(const Surface<2>&, std::span<const Index>, std::span<const Index>, unsigned);

}  // namespace plmap
