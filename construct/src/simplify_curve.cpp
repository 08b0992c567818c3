// simplify_curve(): point removal on a polyline (paper 3.3.1, d = 1). Phases: corner
// classification, the lazily re-ranked priority queue of removable vertices, the merges, and the
// hand-over to MapBuilder<1>. The state is small enough to need no editing unit of its own: each
// live S1 vertex knows its live neighbours along the curve, and the S2 vertices between two live
// neighbours are found by walking S2.

#include <plmap/construct/simplify_curve.hpp>
#include "simplified_map_report.hpp"
#include "simplify_option_checks.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/progress.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <queue>

namespace plmap {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct CurveCosts {
  double hausdorff = 0.0, long_edge = 0.0;
};

CurveCosts curve_costs(const WeightedOracles& oracles) {
  CurveCosts c;
  for (const auto& [name, weight] : oracles.named_weights()) {
    if (name == "hausdorff")
      c.hausdorff += weight;
    else if (name == "long-edge")
      c.long_edge += weight;
    else
      throw Error(fmt::format("error oracle '{}' does not apply to curves (valid for curves: hausdorff, long-edge)", name));
  }
  return c;
}

class CurveSimplifier {
 public:
  CurveSimplifier(const Surface<1>& s, const SimplifyOptions& options, CurveCosts costs)
      : s_(s), options_(options), costs_(costs) {
    const Index nv = s.vertex_count();
    next_.assign(nv, invalid_index);
    prev_.assign(nv, invalid_index);
    corner_.assign(nv, 1);
    live_.assign(nv, 1);
    stamp_.assign(nv, 0);
    last_refusal_.assign(nv, {});
    for (Index e = 0; e < s.element_count(); ++e) {
      const auto& c = s.element(e);
      next_[c[0]] = c[1];
      prev_[c[1]] = c[0];
    }
    double total = 0.0;
    for (Index e = 0; e < s.element_count(); ++e) total += (s.vertex(s.element(e)[1]) - s.vertex(s.element(e)[0])).norm();
    length_scale_ = s.element_count() > 0 ? total / s.element_count() : 1.0;
    const double cos_limit = std::cos(options.feature_angle_degrees * std::numbers::pi / 180.0);
    for (Index v = 0; v < nv; ++v) {
      const auto segments = s.vertex_elements(v);
      // On exactly two segments, one arriving and one leaving: a vertex inside a curve.
      if (segments.size() != 2 || next_[v] == invalid_index || prev_[v] == invalid_index) continue;
      if (s.element(segments[0])[0] == s.element(segments[1])[0]) continue;
      const Eigen::Vector2d in = (s.vertex(v) - s.vertex(prev_[v])).normalized();
      const Eigen::Vector2d out = (s.vertex(next_[v]) - s.vertex(v)).normalized();
      corner_[v] = options.feature_angle_degrees < 180.0 && in.dot(out) < cos_limit;
    }
    live_vertices_ = nv;
    live_segments_ = s.element_count();
  }

  Index corner_count() const {
    Index n = 0;
    for (char c : corner_) n += c;
    return n;
  }
  bool is_corner(Index v) const { return corner_[v] != 0; }
  bool is_live(Index v) const { return live_[v] != 0; }
  const std::string& last_refusal(Index v) const { return last_refusal_[v]; }
  Index live_segments() const { return live_segments_; }
  Index live_vertices() const { return live_vertices_; }

  /// The S2 vertices strictly between the live neighbours of live vertex v and v itself (in
  /// order along the curve), with their arc-length parameter on the segment that would join the
  /// neighbours. Walks S2 from v: a non-corner vertex has one arriving and one leaving segment,
  /// so the walk is unique even when a neighbour is a junction.
  std::vector<std::pair<Index, double>> merged_nodes(Index v) const {
    std::vector<Index> chain;
    for (Index x = s2_prev(v); x != prev_[v]; x = s2_prev(x)) chain.push_back(x);
    std::reverse(chain.begin(), chain.end());
    chain.push_back(v);
    for (Index x = s2_next(v); x != next_[v]; x = s2_next(x)) chain.push_back(x);
    return with_arc_length(prev_[v], chain, next_[v]);
  }
  /// The S2 vertices strictly inside the S1 segment that leaves live vertex u along the S2
  /// segment whose far end is `first_next`, and the live vertex it ends at.
  std::pair<std::vector<std::pair<Index, double>>, Index> segment_nodes(Index u, Index first_next) const {
    std::vector<Index> chain;
    Index x = first_next;
    for (; !live_[x]; x = s2_next(x)) chain.push_back(x);
    return {with_arc_length(u, chain, x), x};
  }

  /// Cost of removing v, or the reason it cannot be removed.
  std::pair<double, std::string> attempt(Index v) const {
    const Index u = prev_[v], w = next_[v];
    if (u == invalid_index || w == invalid_index) return {0.0, "corner"};
    if (u == w || next_[w] == u) return {0.0, "existing_edge"};  // a closed curve keeps 3 vertices
    const Eigen::Vector2d a = s_.vertex(u), b = s_.vertex(w);
    const double length = (b - a).norm();
    if (!(length > 1e-9 * length_scale_)) return {0.0, "degenerate_triangle"};
    double distance = 0.0;
    for (const auto& [x, t] : merged_nodes(v)) {
      // The builder snaps within its tolerance onto a vertex: keep the nodes clear of the ends.
      if (!(t > options_.edit.edge_clearance && t < 1.0 - options_.edit.edge_clearance))
        return {0.0, "node_on_new_edge"};
      distance = std::max(distance, ((1.0 - t) * a + t * b - s_.vertex(x)).norm());
    }
    if (distance > options_.max_error) return {0.0, "max_error"};
    const double relative = length / length_scale_;
    return {costs_.hausdorff * distance / length_scale_ + costs_.long_edge * relative * relative, {}};
  }

  void rank(Index v) {
    ++stamp_[v];
    if (!live_[v] || corner_[v]) return;
    const auto [cost, refusal] = attempt(v);
    last_refusal_[v] = refusal;
    if (refusal.empty()) queue_.push({cost, v, stamp_[v]});
  }

  void run(SimplifyReport& report) {
    for (Index v = 0; v < s_.vertex_count(); ++v) rank(v);
    auto reached = [&] {
      return (options_.target_elements > 0 && live_segments_ <= options_.target_elements) ||
             (options_.target_vertices > 0 && live_vertices_ <= options_.target_vertices);
    };
    while (!queue_.empty() && !reached()) {
      const Entry top = queue_.top();
      queue_.pop();
      if (top.stamp != stamp_[top.vertex] || !live_[top.vertex]) continue;
      // Removals elsewhere may have changed what this one would do (a closed curve shrinking to
      // three vertices): plan it again on the current state.
      const auto [cost, refusal] = attempt(top.vertex);
      last_refusal_[top.vertex] = refusal;
      if (!refusal.empty()) {
        ++stamp_[top.vertex];
        continue;
      }
      if (cost > top.cost + 1e-12 * (1.0 + std::abs(top.cost))) {
        ++stamp_[top.vertex];
        queue_.push({cost, top.vertex, stamp_[top.vertex]});
        continue;
      }
      const Index u = prev_[top.vertex], w = next_[top.vertex];
      live_[top.vertex] = 0;
      next_[u] = w;
      prev_[w] = u;
      --live_vertices_;
      --live_segments_;
      ++report.removed_vertices;
      rank(u);
      rank(w);
      if (options_.progress && options_.progress_every > 0 && report.removed_vertices % options_.progress_every == 0)
        report_removals(report, false);
    }
    report.target_reached = reached();
  }

  /// The "removing vertices" progress (see SimplifyOptions::progress), in segments removed
  /// towards the target; `finished`: the phase is over, whether or not the target was reached.
  void report_removals(const SimplifyReport& report, bool finished) const {
    std::uint64_t done = static_cast<std::uint64_t>(report.removed_vertices), total = 0;
    if (options_.target_elements > 0) {
      total = static_cast<std::uint64_t>(std::max<Index>(0, report.elements_before - options_.target_elements));
      done = static_cast<std::uint64_t>(std::max<Index>(0, report.elements_before - live_segments_));
    } else if (options_.target_vertices > 0) {
      total = static_cast<std::uint64_t>(std::max<Index>(0, report.vertices_before - options_.target_vertices));
    }
    if (total > 0)
      done = finished ? total : std::min(done, total);
    else if (finished)
      total = done;
    report_progress(options_.progress, "removing vertices", done, total);
  }

 private:
  struct Entry {
    double cost;
    Index vertex;
    std::uint32_t stamp;
    bool operator>(const Entry& o) const { return cost > o.cost || (cost == o.cost && vertex > o.vertex); }
  };
  /// S2's neighbours along the curve (unique at a non-corner vertex).
  Index s2_next(Index x) const {
    for (Index e : s_.vertex_elements(x))
      if (s_.element(e)[0] == x) return s_.element(e)[1];
    return invalid_index;
  }
  Index s2_prev(Index x) const {
    for (Index e : s_.vertex_elements(x))
      if (s_.element(e)[1] == x) return s_.element(e)[0];
    return invalid_index;
  }
  std::vector<std::pair<Index, double>> with_arc_length(Index u, const std::vector<Index>& chain, Index w) const {
    std::vector<std::pair<Index, double>> out;
    double length = 0.0;
    Index previous = u;
    for (Index x : chain) {
      length += (s_.vertex(x) - s_.vertex(previous)).norm();
      out.emplace_back(x, length);
      previous = x;
    }
    length += (s_.vertex(w) - s_.vertex(previous)).norm();
    for (auto& [x, t] : out) t /= length;
    return out;
  }

  const Surface<1>& s_;
  const SimplifyOptions& options_;
  CurveCosts costs_;
  double length_scale_ = 1.0;
  std::vector<Index> next_, prev_;  ///< live neighbours along the curve (S1)
  std::vector<char> corner_, live_;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::string> last_refusal_;
  Index live_vertices_ = 0, live_segments_ = 0;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
};

}  // namespace

CurveSimplifyResult simplify_curve(std::shared_ptr<const Surface<1>> fine, SimplifyOptions options) {
  const auto start = Clock::now();
  if (!fine) throw Error("simplify: no curve given");
  const Surface<1>& s = *fine;
  detail::check_simplify_options(options, s.element_count(), s.vertex_count(), "curve", "segments");
  detail::check_no_isolated_vertices(s, "curve", "segments");
  if (options.oracles.empty()) options.oracles.add("hausdorff", 1.0).add("long-edge", 0.05);
  const CurveCosts costs = curve_costs(options.oracles);

  SimplifyReport report;
  report.elements_before = s.element_count();
  report.vertices_before = s.vertex_count();
  report.oracles = options.oracles.description();
  CurveSimplifier simplifier(s, options, costs);
  report.feature_corners = simplifier.corner_count();
  report.feature_vertices = report.feature_corners;
  simplifier.run(report);
  report.seconds_simplify = seconds_since(start);
  simplifier.report_removals(report, true);
  for (Index v = 0; v < s.vertex_count(); ++v) {
    if (!simplifier.is_live(v) || simplifier.is_corner(v) || simplifier.last_refusal(v).empty()) continue;
    ++report.skipped_by_reason[simplifier.last_refusal(v)];
    ++report.skipped_vertices;
  }

  // S1: the live vertices in S2's order, a segment from each live vertex to its live successor.
  const auto finalize_start = Clock::now();
  std::vector<Index> number(s.vertex_count(), invalid_index);
  std::vector<WorldPoint<1>> vertices;
  for (Index v = 0; v < s.vertex_count(); ++v)
    if (simplifier.is_live(v)) {
      number[v] = static_cast<Index>(vertices.size());
      vertices.push_back(s.vertex(v));
    }
  // An S1 segment starts at every live vertex along each S2 segment leaving it, and runs along
  // S2 to the next live vertex.
  std::vector<ElementCorners<1>> segments;
  std::vector<std::vector<std::pair<Index, double>>> inside;
  for (Index e = 0; e < s.element_count(); ++e) {
    const Index u = s.element(e)[0];
    if (!simplifier.is_live(u)) continue;
    auto [nodes, w] = simplifier.segment_nodes(u, s.element(e)[1]);
    segments.push_back({number[u], number[w]});
    inside.push_back(std::move(nodes));
  }
  auto domain = std::make_shared<const Surface<1>>(std::move(vertices), std::move(segments));
  BuilderOptions builder_options = options.builder;
  if (builder_options.orientation == 0) builder_options.orientation = 1;
  MapBuilder<1> builder(domain, fine, builder_options);
  for (Index v = 0; v < s.vertex_count(); ++v)
    if (simplifier.is_live(v)) builder.add_vertex_preimage_at_vertex(v, number[v]);
  for (std::size_t k = 0; k < inside.size(); ++k)
    for (const auto& [x, t] : inside[k]) {
      LocalPoint<1> local;
      local(0) = t;
      builder.add_vertex_preimage(x, {static_cast<Index>(k), local});
    }
  for (Index e = 0; e < s.element_count(); ++e) builder.add_edge(e);
  PlMap<1> map = std::move(builder).finalize();
  report.seconds_finalize = seconds_since(finalize_start);
  detail::report_simplified_map(map, s, report);
  report.seconds_total = seconds_since(start);
  return {std::move(map), std::move(report)};
}

}  // namespace plmap
