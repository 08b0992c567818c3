#pragma once
// Private to plmap::verify: the shared state of the checks (what every check needs computed once)
// and the sink that records violations with a bounded amount of detail.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/verify/options.hpp>
#include <plmap/verify/report.hpp>

#include <fmt/format.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace plmap::detail {

/// Records the violations of one check. Formatting a message costs more than checking, so the
/// message is produced by a callable and only when the violation is stored in full.
class ViolationSink {
 public:
  ViolationSink(CheckResult& result, std::size_t max_per_rule)
      : result_(result), max_per_rule_(max_per_rule) {}

  struct Where {
    Index element = invalid_index;
    Index node = invalid_index;
    Index region = invalid_index;
    Index target_element = invalid_index;
  };

  template <class MakeMessage>
  void add(std::string_view rule, Where where, MakeMessage&& make_message) {
    ++result_.violation_count;
    auto it = result_.rule_counts.find(std::string(rule));
    if (it == result_.rule_counts.end()) it = result_.rule_counts.emplace(std::string(rule), 0).first;
    if (it->second++ >= max_per_rule_) return;
    Violation v;
    v.check = result_.name;
    v.rule = std::string(rule);
    v.element = where.element;
    v.node = where.node;
    v.region = where.region;
    v.target_element = where.target_element;
    v.message = make_message();
    result_.violations.push_back(std::move(v));
  }

  std::size_t count() const { return result_.violation_count; }

 private:
  CheckResult& result_;
  std::size_t max_per_rule_;
};

/// What the checks share: the map, its arrays, the owner element of every node, and the
/// scale-relative tolerances.
template <int d>
struct MapContext {
  MapContext(const PlMap<d>& m, const VerifyOptions& o)
      : map(m), data(m.data()), s1(m.domain()), s2(m.target()), options(o) {
    const Index nt = s1.element_count();
    node_element.resize(data.node_type.size());
    for (Index t = 0; t < nt; ++t)
      for (Index n = data.node_begin[t]; n < data.node_begin[t + 1]; ++n) node_element[n] = t;
    world_tolerance_s1 = o.world_tolerance * s1.max_edge_length();
    world_tolerance_s2 = o.world_tolerance * s2.max_edge_length();
  }

  const PlMap<d>& map;
  const MapData<d>& data;
  const Surface<d>& s1;
  const Surface<d>& s2;
  VerifyOptions options;
  std::vector<Index> node_element;
  double world_tolerance_s1 = 0.0;
  double world_tolerance_s2 = 0.0;

  Index element_count() const { return s1.element_count(); }
  Index nodes_begin(Index t) const { return data.node_begin[t]; }
  Index nodes_end(Index t) const { return data.node_begin[t + 1]; }
  Index regions_begin(Index t) const { return data.region_begin[t]; }
  Index regions_end(Index t) const { return data.region_begin[t + 1]; }
  Index region_element(Index r) const { return node_element[data.region_corners[r][0]]; }
};

// ---- small geometry on local coordinates ---------------------------------------------------

inline Eigen::Vector2d as_vec2(const LocalPoint<2>& p) { return p; }

/// Barycentric coordinates of a point with respect to a triangle or segment given by local
/// corner positions (floating point; used only with tolerances, never for a combinatorial sign).
template <int d>
Barycentric<d> barycentric_in(const std::array<LocalPoint<d>, d + 1>& c, const LocalPoint<d>& p) {
  Barycentric<d> b;
  if constexpr (d == 1) {
    const double len = c[1](0) - c[0](0);
    const double t = len != 0.0 ? (p(0) - c[0](0)) / len : std::numeric_limits<double>::quiet_NaN();
    b << 1.0 - t, t;
  } else {
    Eigen::Matrix2d m;
    m.col(0) = c[1] - c[0];
    m.col(1) = c[2] - c[0];
    const double det = m.determinant();
    if (det == 0.0) {
      b.setConstant(std::numeric_limits<double>::quiet_NaN());
      return b;
    }
    const Eigen::Vector2d x = m.inverse() * (p - c[0]);
    b << 1.0 - x.sum(), x(0), x(1);
  }
  return b;
}

/// Where a local position lies on the reference element, decided with the snap tolerance.
struct LocalPlace {
  enum Kind { corner, edge, interior, outside } kind = interior;
  int index = -1;  ///< the corner or local edge, -1 for interior/outside
};

template <int d>
LocalPlace classify_local(const LocalPoint<d>& xi, double snap) {
  const Barycentric<d> b = barycentric_from_local<d>(xi);
  int near_zero = 0, nonzero_index = -1, zero_index = -1;
  for (int i = 0; i <= d; ++i) {
    if (!(b(i) >= -snap)) return {LocalPlace::outside, -1};
    if (std::abs(b(i)) <= snap) {
      ++near_zero;
      zero_index = i;
    } else {
      nonzero_index = i;
    }
  }
  if (near_zero == d) return {LocalPlace::corner, nonzero_index};
  if (d == 2 && near_zero == 1) return {LocalPlace::edge, (zero_index + 1) % 3};  // edge k is opposite corner k+2
  if (near_zero == 0) return {LocalPlace::interior, -1};
  return {LocalPlace::outside, -1};  // all coordinates near zero: not a point of the element
}

/// Parameter of a local position along local edge k of a triangle (0 at corner k, 1 at k+1).
inline double edge_parameter(const LocalPoint<2>& xi, int k) {
  return barycentric_from_local<2>(xi)((k + 1) % 3);
}

/// Parameter along the global S1 edge of local edge k of element t, from its smaller-index
/// vertex, so that all copies of a node on the edge get the same number.
inline double global_edge_parameter(const Surface<2>& s, Index t, int k, const LocalPoint<2>& xi) {
  const Barycentric<2> b = barycentric_from_local<2>(xi);
  return s.local_edge_is_forward(t, k) ? b((k + 1) % 3) : b(k);
}

/// Local position on element t at parameter s (from the smaller-index vertex) of local edge k.
inline LocalPoint<2> point_on_global_edge(const Surface<2>& s1, Index t, int k, double s) {
  const double to_next = s1.local_edge_is_forward(t, k) ? s : 1.0 - s;
  return (1.0 - to_next) * reference_corner<2>(k) + to_next * reference_corner<2>((k + 1) % 3);
}

/// True if the image point (S2 element and local coordinates) is inside its element.
template <int d>
double min_barycentric(const LocalPoint<d>& xi) {
  return barycentric_from_local<d>(xi).minCoeff();
}

template <int d>
std::string fmt_point(const Eigen::Matrix<double, d, 1>& p) {
  std::string s = "(";
  for (int i = 0; i < d; ++i) s += (i ? ", " : "") + fmt::format("{:.17g}", p(i));
  return s + ")";
}


// ---- candidate pairs for the pairwise tests ------------------------------------------------

/// Axis-aligned box of a segment or triangle in the plane.
struct Box2 {
  double xmin, xmax, ymin, ymax;
  bool overlaps(const Box2& o) const {
    return xmin <= o.xmax && o.xmin <= xmax && ymin <= o.ymax && o.ymin <= ymax;
  }
};

/// Calls on_pair(i, j), i != j, once for every pair of boxes that overlap (closed boxes).
/// Few boxes: all pairs. Many: a uniform grid of about one box per cell, and a pair is tested
/// only in the cell where the ranges of cells of both boxes begin to overlap, so each pair is
/// seen once without a hash set. Linear for boxes of bounded size relative to their spacing
/// (the case of refinements with 10^5 regions in one element).
class OverlapGrid {
 public:
  template <class OnPair>
  void for_each_pair(const std::vector<Box2>& boxes, OnPair&& on_pair) {
    const std::size_t n = boxes.size();
    if (n <= 48) {
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
          if (boxes[i].overlaps(boxes[j])) on_pair(i, j);
      return;
    }
    Box2 all = boxes[0];
    for (const Box2& b : boxes) {
      all.xmin = std::min(all.xmin, b.xmin);
      all.xmax = std::max(all.xmax, b.xmax);
      all.ymin = std::min(all.ymin, b.ymin);
      all.ymax = std::max(all.ymax, b.ymax);
    }
    const int g = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(n))), 1, 4096);
    const double w = all.xmax > all.xmin ? (all.xmax - all.xmin) / g : 1.0;
    const double h = all.ymax > all.ymin ? (all.ymax - all.ymin) / g : 1.0;
    auto cx = [&](double x) { return std::clamp(static_cast<int>((x - all.xmin) / w), 0, g - 1); };
    auto cy = [&](double y) { return std::clamp(static_cast<int>((y - all.ymin) / h), 0, g - 1); };
    range_.resize(n);
    begin_.assign(static_cast<std::size_t>(g) * g + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      range_[i] = {cx(boxes[i].xmin), cx(boxes[i].xmax), cy(boxes[i].ymin), cy(boxes[i].ymax)};
      for (int y = range_[i][2]; y <= range_[i][3]; ++y)
        for (int x = range_[i][0]; x <= range_[i][1]; ++x) ++begin_[static_cast<std::size_t>(y) * g + x + 1];
    }
    for (std::size_t c = 1; c < begin_.size(); ++c) begin_[c] += begin_[c - 1];
    members_.resize(begin_.back());
    fill_.assign(begin_.begin(), begin_.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      for (int y = range_[i][2]; y <= range_[i][3]; ++y)
        for (int x = range_[i][0]; x <= range_[i][1]; ++x)
          members_[fill_[static_cast<std::size_t>(y) * g + x]++] = static_cast<Index>(i);
    for (int y = 0; y < g; ++y)
      for (int x = 0; x < g; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * g + x;
        for (std::size_t a = begin_[c]; a < begin_[c + 1]; ++a)
          for (std::size_t b = a + 1; b < begin_[c + 1]; ++b) {
            const Index i = members_[a], j = members_[b];
            // Test the pair only in the first cell both boxes share.
            if (std::max(range_[i][0], range_[j][0]) != x || std::max(range_[i][2], range_[j][2]) != y)
              continue;
            if (boxes[i].overlaps(boxes[j])) on_pair(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
          }
      }
  }

 private:
  std::vector<std::array<int, 4>> range_;
  std::vector<std::size_t> begin_, fill_;
  std::vector<Index> members_;
};

// ---- the checks, each recording into a sink; the index check gates all others --------------

template <int d>
bool check_indices(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_structure(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_plane_graph(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_minimal_embedding(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_map(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_continuity(const MapContext<d>& ctx, ViolationSink& sink);
template <int d>
void run_coverage(const MapContext<d>& ctx, ViolationSink& sink);

/// What evaluating the stored affine map `a` at a local point (coordinates in [0, 1]) can be
/// off by in each image coordinate through rounding alone: a few units in the last place of the
/// largest term of the sum. A region whose preimage is a sliver has a map with huge entries (seen
/// on CGAL's dino simplified with the aspect-ratio and long-edge oracles only: stretch 1.25e6),
/// and evaluated at its own corners it lands 2^-29 ~ 1.9e-9 outside its S2 triangle: not a
/// defect of the map, but of reading it in doubles. The checks that evaluate region maps (map:
/// corner images; continuity: both sides of an edge; coverage: image areas and pairwise
/// overlaps) add this to their tolerances; for any map that is not stretched by millions it is
/// ~1e-15.
template <int d>
double region_map_rounding(const AffineMap<d>& a) {
  double largest = 0.0;
  for (int i = 0; i < d; ++i) {
    double row = std::abs(a(i, d));
    for (int j = 0; j < d; ++j) row += std::abs(a(i, j));
    largest = std::max(largest, row);
  }
  return 8.0 * std::numeric_limits<double>::epsilon() * largest;
}

/// A rounding of local coordinates on S2 in space: at most the longest S2 edge per unit, per
/// coordinate.
template <int d>
double rounding_in_space(double local_rounding, const Surface<d>& s2) {
  return 2.0 * local_rounding * s2.max_edge_length();
}

}  // namespace plmap::detail
