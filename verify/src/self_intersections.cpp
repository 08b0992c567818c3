// Pairs of elements that meet without sharing a vertex (self_intersections.hpp).
//
// The candidates are the pairs of elements whose bounding boxes meet, found in one sweep over all
// boxes (CGAL's box intersection); each candidate that shares no vertex is then decided with exact
// predicates, in pieces on all threads. (The first version queried the ray check's AABB tree once
// per element, with each curve segment extruded to two triangles in space: on a 1M-segment curve
// `plmap info` took 4.3 s and 490 MB for it, docs/benchmarks.md.)

#include <plmap/verify/self_intersections.hpp>

#include <plmap/core/parallel_ranges.hpp>

#include <CGAL/Box_intersection_d/Box_with_handle_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <numeric>

namespace plmap {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

template <int d>
bool share_a_vertex(const Surface<d>& s, Index a, Index b) {
  const auto& of_a = s.element(a);
  for (Index v : s.element(b))
    if (std::find(of_a.begin(), of_a.end(), v) != of_a.end()) return true;
  return false;
}

/// Whether elements a and b meet, by CGAL's exact predicates. An element that is degenerate in
/// exact arithmetic (a surface refuses elements of zero measure, but the measure it computes in
/// doubles may be the rounding of exactly collinear corners) meets nothing: CGAL's triangle test
/// requires proper triangles.
template <int d>
bool elements_meet(const Surface<d>& s, Index a, Index b) {
  if constexpr (d == 2) {
    auto triangle = [&](Index t) {
      auto p = [&](int k) {
        const WorldPoint<2> q = s.corner(t, k);
        return Kernel::Point_3(q.x(), q.y(), q.z());
      };
      return Kernel::Triangle_3(p(0), p(1), p(2));
    };
    const Kernel::Triangle_3 ta = triangle(a), tb = triangle(b);
    return !ta.is_degenerate() && !tb.is_degenerate() && CGAL::do_intersect(ta, tb);
  } else {
    auto segment = [&](Index t) {
      auto p = [&](int k) {
        const WorldPoint<1> q = s.corner(t, k);
        return Kernel::Point_2(q.x(), q.y());
      };
      return Kernel::Segment_2(p(0), p(1));
    };
    const Kernel::Segment_2 sa = segment(a), sb = segment(b);
    return !sa.is_degenerate() && !sb.is_degenerate() && CGAL::do_intersect(sa, sb);
  }
}

/// The candidates, decided in batches on all threads: memory for one batch and the answer, not
/// for every candidate at once (a soup of long thin elements has boxes that nearly all overlap).
template <int d>
class MeetingPairs {
 public:
  MeetingPairs(const Surface<d>& s, unsigned threads) : s_(s), threads_(threads) {}

  void add_candidate(Index a, Index b) {
    batch_.emplace_back(std::min(a, b), std::max(a, b));
    if (batch_.size() == batch_size) decide_batch();
  }

  /// The pairs that meet, sorted.
  std::vector<std::pair<Index, Index>> take() {
    decide_batch();
    std::sort(found_.begin(), found_.end());
    return std::move(found_);
  }

 private:
  static constexpr std::size_t batch_size = std::size_t{1} << 20;

  void decide_batch() {
    meet_.assign(batch_.size(), 0);
    parallel_for_chunks(batch_.size(), 4096, threads_, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) meet_[i] = elements_meet(s_, batch_[i].first, batch_[i].second);
    });
    for (std::size_t i = 0; i < batch_.size(); ++i)
      if (meet_[i]) found_.push_back(batch_[i]);
    batch_.clear();
  }

  const Surface<d>& s_;
  unsigned threads_;
  std::vector<std::pair<Index, Index>> batch_, found_;
  std::vector<char> meet_;
};

/// An element's box over N of the coordinate axes. The handle points at the element's entry in a
/// list of element numbers: CGAL copies the boxes for a self-intersection sweep and tells boxes
/// apart by their ids, which the handle's address gives and the copies keep.
template <int N>
using ElementBox = CGAL::Box_intersection_d::Box_with_handle_d<double, N, const Index*>;

/// The axes the boxes are taken over, in the order the boxes take them. CGAL's sweep splits the
/// boxes along its last dimension first and scans them sorted along its first, and slows to a
/// near-quadratic scan where all boxes span the same interval in either: so the widest axis comes
/// first and the thinnest in the middle (three axes) or last (two), and an axis along which the
/// surface does not extend at all (a planar mesh in space, a straight curve) is left out.
template <int d>
std::vector<int> box_axes(const Surface<d>& s) {
  const WorldPoint<d> extent = s.bounding_box_max() - s.bounding_box_min();
  std::vector<int> axes;
  for (int i = 0; i <= d; ++i)
    if (extent[i] > 0.0) axes.push_back(i);
  std::sort(axes.begin(), axes.end(), [&](int i, int j) { return extent[i] > extent[j]; });
  if (axes.size() == 3) std::swap(axes[1], axes[2]);  // widest, thinnest, the other
  return axes;
}

/// Hands `out` the pairs of elements whose boxes over `axes` (N of them) meet and which share no
/// vertex. Boxes are closed: elements that only touch are candidates too.
template <int N, int d>
void add_candidates(const Surface<d>& s, const std::vector<int>& axes, MeetingPairs<d>& out) {
  std::vector<Index> elements(static_cast<std::size_t>(s.element_count()));
  std::iota(elements.begin(), elements.end(), Index{0});
  std::vector<ElementBox<N>> boxes;
  boxes.reserve(elements.size());
  for (const Index& t : elements) {
    std::array<double, N> low, high;
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    for (int k = 0; k <= d; ++k) {
      const WorldPoint<d>& p = s.corner(t, k);
      for (int i = 0; i < N; ++i) {
        low[i] = std::min(low[i], p[axes[i]]);
        high[i] = std::max(high[i], p[axes[i]]);
      }
    }
    boxes.emplace_back(low.data(), high.data(), &t);
  }
  // Below this many boxes the sweep scans instead of splitting further. CGAL's default, 10, made
  // `plmap info` on the L7 sphere 0.88 s against 0.50 s with 1000 (0.27 against 0.18 s on the
  // armadillo pair's S2; 500 and 2000 about as 1000; docs/benchmarks.md).
  constexpr std::ptrdiff_t scan_below = 1000;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const ElementBox<N>& x, const ElementBox<N>& y) {
    const Index a = *x.handle(), b = *y.handle();
    if (!share_a_vertex(s, a, b)) out.add_candidate(a, b);
  }, scan_below);
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
std::vector<std::pair<Index, Index>> self_intersections(const Surface<d>& s, unsigned threads) {
  const std::vector<int> axes = box_axes(s);
  MeetingPairs<d> pairs(s, threads);
  switch (axes.size()) {
    case 1: add_candidates<1>(s, axes, pairs); break;
    case 2: add_candidates<2>(s, axes, pairs); break;
    default: add_candidates<3>(s, axes, pairs); break;
  }
  return pairs.take();
}

template std::vector<std::pair<Index, Index>> self_intersections<1>(const Surface<1>&, unsigned);
template std::vector<std::pair<Index, Index>> self_intersections<2>(const Surface<2>&, unsigned);

}  // namespace plmap
