// simplify(): the driver of paper 3.3.1. Phases: feature classification, the priority queue of
// removal candidates (ranked by the error oracles, lazily re-ranked after each step), the steps
// themselves (EditableMap plans and applies them), and the hand-over to MapBuilder.

#include <plmap/construct/simplify.hpp>
#include "simplified_map_report.hpp"
#include "simplify_option_checks.hpp"
#include "simplify_ranking_estimate.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/strategies/simplification/simplification_registry.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <queue>
#include <unordered_set>

namespace plmap {

std::vector<char> feature_edges(const Surface<2>& surface, double feature_angle_degrees) {
  const double cos_limit = std::cos(feature_angle_degrees * std::numbers::pi / 180.0);
  std::vector<char> feature(surface.edge_count(), 0);
  for (Index e = 0; e < surface.edge_count(); ++e) {
    const auto incident = surface.edge_elements(e);
    if (incident.size() != 2) {
      feature[e] = 1;
      continue;
    }
    // Two triangles that run through the edge in the same direction are oriented inconsistently:
    // the polar map cannot flatten across them, so the edge is a feature.
    if (surface.local_edge_is_forward(incident[0].element, incident[0].local_edge) ==
        surface.local_edge_is_forward(incident[1].element, incident[1].local_edge)) {
      feature[e] = 1;
      continue;
    }
    const double cosine = surface.element_normal(incident[0].element).dot(surface.element_normal(incident[1].element));
    if (feature_angle_degrees < 180.0 && cosine < cos_limit) feature[e] = 1;
  }
  return feature;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// One removal attempt: the plan and the oracles' verdict, or why it cannot be done.
struct Attempt {
  VertexRemovalPlan plan;
  OracleVerdict verdict;
  std::string refusal;  // empty if admissible
  bool perturbed = false;  ///< planned on a perturbed flattening (Simplifier::perturb)
};

class Simplifier {
 public:
  Simplifier(std::shared_ptr<const Surface<2>> fine, SimplifyOptions& options)
      : options_(options),
        map_(fine, options.edit),
        flatten_(make_star_flattening(options.flattening)),
        flatten_half_(make_half_star_flattening(options.flattening)),
        triangulate_(make_hole_triangulation(options.hole_triangulation)),
        estimate_(map_),
        estimated_(options.ranking == "estimate") {
    const Surface<2>& s = *fine;
    for (const auto& [name, weight] : options.oracles.named_weights()) {
      if (name == "hausdorff") hausdorff_weight_ += weight;
      if (name == "aspect-ratio") aspect_weight_ += weight;
    }
    double total = 0.0;
    for (Index e = 0; e < s.edge_count(); ++e) {
      const auto ab = s.edge_vertices(e);
      total += (s.vertex(ab[0]) - s.vertex(ab[1])).norm();
    }
    length_scale_ = s.edge_count() > 0 ? total / s.edge_count() : 1.0;
    // A vertex with exactly two feature edges lies on a feature line and is removed along it;
    // any other vertex with feature edges is a feature corner and stays.
    const std::vector<char> feature = feature_edges(s, options.feature_angle_degrees);
    feature_vertex_.assign(s.vertex_count(), 0);
    line_neighbours_.assign(s.vertex_count(), {invalid_index, invalid_index});
    std::vector<int> feature_degree(s.vertex_count(), 0);
    for (Index e = 0; e < s.edge_count(); ++e)
      if (feature[e]) {
        ++feature_edge_count_;
        const auto ab = s.edge_vertices(e);
        feature_s1_edges_.insert(edge_key(ab[0], ab[1]));
        for (int m = 0; m < 2; ++m) {
          const Index v = ab[m];
          feature_vertex_[v] = 1;
          if (feature_degree[v] < 2) line_neighbours_[v][feature_degree[v]] = ab[1 - m];
          ++feature_degree[v];
        }
      }
    // A line that turns by more than the feature angle at a vertex has a corner there too (the
    // corner of a square's boundary), as for curves.
    const double cos_limit = std::cos(options.feature_angle_degrees * std::numbers::pi / 180.0);
    corner_.assign(s.vertex_count(), 0);
    for (Index v = 0; v < s.vertex_count(); ++v) {
      corner_[v] = feature_degree[v] != 0 && feature_degree[v] != 2;
      if (feature_degree[v] == 2 && options.feature_angle_degrees < 180.0) {
        const Eigen::Vector3d in = (s.vertex(v) - s.vertex(line_neighbours_[v][0])).normalized();
        const Eigen::Vector3d out = (s.vertex(line_neighbours_[v][1]) - s.vertex(v)).normalized();
        corner_[v] = in.dot(out) < cos_limit;
      }
    }
    stamp_.assign(s.vertex_count(), 0);
    last_refusal_.assign(s.vertex_count(), {});
    prepared_.resize(static_cast<std::size_t>(s.vertex_count()));
    new_edges_.assign(s.vertex_count(), 0);
    perturbed_preimage_.assign(s.vertex_count(), 0);
  }

  Index feature_edge_count() const { return feature_edge_count_; }
  Index feature_vertex_count() const {
    Index n = 0;
    for (char f : feature_vertex_) n += f;
    return n;
  }
  Index feature_corner_count() const {
    Index n = 0;
    for (char f : corner_) n += f;
    return n;
  }
  bool is_corner(Index v) const { return corner_[v] != 0; }
  const std::vector<std::string>& last_refusal() const { return last_refusal_; }
  bool is_feature(Index v) const { return feature_vertex_[v] != 0; }
  EditableMap& map() { return map_; }

  /// Plans the removal of v (fully, or only its ranking bound) and judges it.
  Attempt attempt(Index v, PlanExtent extent) {
    if (line_neighbours_[v][0] != invalid_index && !is_corner(v)) return attempt_along_line(v, extent);
    Attempt a;
    PreparedHole& hole = prepared_[v];
    // A vertex queued again after its full plan comes up with that plan when nothing it copied
    // has changed since (EditableMap::refresh_plan) and the hole would be triangulated the same
    // (see below): the plan is the one planning again would make.
    if (extent == PlanExtent::full && hole.has_full_plan && hole.stamp == stamp_[v] && !hole.sheet.ring.empty() &&
        hole.new_edge_count == new_edges_at(hole.sheet.ring)) {
      hole.has_full_plan = false;
      if (map_.refresh_plan(*hole.full_plan)) {
        a.plan = std::move(*hole.full_plan);
        a.perturbed = hole.perturbed;
        return judge(std::move(a));
      }
      give_back(std::move(*hole.full_plan));
    }
    a.plan = spare_plan();  // its buffers, for this plan
    a.plan.reset();
    a.plan.vertex = v;
    // The full plan of a popped vertex reuses its ranking's hole when the triangulation would
    // come out the same: the star is unchanged (same stamp) and every S1 edge the
    // triangulation asked about is still there or still absent.
    if (extent == PlanExtent::full && hole.stamp == stamp_[v] && !hole.sheet.ring.empty() &&
        hole.new_edge_count == new_edges_at(hole.sheet.ring)) {
      // Right after confirm_estimate accepted v's ranking plan (made on this hole), the full plan
      // continues from it (EditableMap::plan_vertex_removal's `storage`).
      if (confirmed_.vertex == v) {
        give_back(std::move(a.plan));
        a.plan = std::move(confirmed_);
        confirmed_.vertex = invalid_index;
      }
      a.plan = map_.plan_vertex_removal(v, std::span(&hole.sheet, 1), std::span(&hole.flat, 1),
                                        std::span(&hole.triangles, 1), extent, std::move(a.plan));
      a.perturbed = hole.perturbed;
      return judge(std::move(a));
    }
    hole.sheet.ring.clear();
    if (hole.has_full_plan) give_back(std::move(*hole.full_plan));
    hole.has_full_plan = false;
    std::vector<Index> ring = map_.closed_ring(v);
    if (ring.size() < 3) {
      a.refusal = to_string(RemovalRefusal::not_a_disk_star);
      return a;
    }
    std::vector<Eigen::Vector3d>& ring_positions = hole_buffers_.ring_positions;
    ring_positions.clear();
    for (Index w : ring) ring_positions.push_back(map_.position(w));
    auto flat = flatten_(map_.position(v), ring_positions);
    if (!flat) {
      a.refusal = to_string(RemovalRefusal::flattening_not_simple);
      return a;
    }
    // Diagonals through a node of the star (common in regular meshes, whose stars are
    // symmetric) are avoided by triangulating again without them; where every triangulation
    // has one (a flat regular grid, coarsened far: its nodes lie on every straight line between
    // grid points, and v itself on the line between opposite ring vertices), the flattening is
    // perturbed once and the hole planned again.
    // The one-sheet lists are those of hole_buffers_ (moved in, not copied from initializer
    // lists); plan_on_perturbed_flattening may replace `flats` by another list of one flattening.
    std::vector<StarSheet>& sheet = hole_buffers_.sheet;
    std::vector<std::vector<Eigen::Vector2d>>& flats = hole_buffers_.flats;
    std::vector<HoleTriangles>& triangles = hole_buffers_.triangles;
    sheet[0].ring = std::move(ring);
    sheet[0].closed = true;
    flats[0] = std::move(*flat);
    triangles[0].clear();
    HolePlanning planning = plan_avoiding_nodes(v, sheet, flats, triangles, extent, a);
    if (blocked_by_a_node(a, planning)) planning = plan_on_perturbed_flattening(v, sheet, flats, triangles, extent, a, planning);
    if (planning != HolePlanning::planned) {
      a.refusal = to_string(out_of_triangulations(a, planning));
      return a;
    }
    a = judge(std::move(a));
    if (a.refusal.empty()) {
      hole.sheet = std::move(sheet[0]);
      hole.flat = std::move(flats[0]);
      hole.triangles = std::move(triangles[0]);
      hole.stamp = stamp_[v];
      hole.new_edge_count = new_edges_at(hole.sheet.ring);
      hole.perturbed = a.perturbed;
    }
    return a;
  }

  /// The flattening and triangulation of a closed star from its ranking, for its full plan.
  /// The hole triangulation is a deterministic function of the polygon and of the answers of
  /// `allowed`, which depend on the S1 edges between ring vertices. Such an edge disappears only
  /// with a ring vertex (then v is ranked again: a new stamp) and appears only as a new edge of
  /// a removal, whose ends all get their new_edges_ count raised: an unchanged sum over the ring
  /// means unchanged answers.
  struct PreparedHole {
    std::uint32_t stamp = 0;
    std::uint64_t new_edge_count = 0;  ///< sum of new_edges_ over the ring when triangulated
    StarSheet sheet;                   ///< empty ring: nothing kept
    std::vector<Eigen::Vector2d> flat;
    HoleTriangles triangles;
    bool perturbed = false;            ///< flat is a perturbed flattening
    bool has_full_plan = false;        ///< full_plan holds the full plan made when v was queued again
    /// Out of line: one PreparedHole per S2 vertex, but few vertices ever keep a plan, and a plan
    /// inline made every PreparedHole about 400 bytes (11 MB of the armadillo's first touches,
    /// page faults, and zeroing in the constructor). Kept once made, for its buffers.
    std::unique_ptr<VertexRemovalPlan> full_plan;
  };
  /// The lists of one attempt on a closed star, kept for the next attempt: made afresh, they
  /// were about six allocations per attempt, and the ring and the flattening were copied out of
  /// initializer lists. An accepted attempt's ring, flattening and triangulation move on into
  /// its PreparedHole; the next attempt assigns every element before it reads one, and only the
  /// elements are moved out, so each outer list keeps its one element.
  struct HoleBuffers {
    std::vector<Eigen::Vector3d> ring_positions;
    std::vector<StarSheet> sheet = std::vector<StarSheet>(1);
    std::vector<std::vector<Eigen::Vector2d>> flats = std::vector<std::vector<Eigen::Vector2d>>(1);
    std::vector<HoleTriangles> triangles = std::vector<HoleTriangles>(1);
  };
  HoleBuffers hole_buffers_;
  std::uint64_t new_edges_at(const std::vector<Index>& ring) const {
    std::uint64_t sum = 0;
    for (Index w : ring) sum += new_edges_[w];
    return sum;
  }

  /// The removal of v along its feature line: each side of the line (half-star) is flattened
  /// onto a half-disk and re-triangulated on its own; the new edge joins the line neighbours.
  Attempt attempt_along_line(Index v, PlanExtent extent) const {
    Attempt a;
    a.plan.vertex = v;
    const auto [left, right] = line_neighbours_[v];
    // v's line neighbours joined by a feature edge as well: the line closes a loop of three
    // feature edges here (the rim of a hole down to three vertices, or a triangle between
    // corners), which removing v would collapse onto one edge. Such a loop keeps its vertices,
    // as a closed curve keeps three. (The plan would refuse it as existing_edge, or earlier as
    // single_triangle_side; this names why.)
    if (feature_s1_edges_.contains(edge_key(left, right))) {
      a.refusal = "feature_loop_of_three";
      return a;
    }
    std::vector<StarSheet> sheets = map_.line_star_sheets(v, left, right);
    if (sheets.empty()) {
      a.refusal = to_string(RemovalRefusal::not_a_disk_star);
      return a;
    }
    std::vector<std::vector<Eigen::Vector2d>> flat;
    for (const StarSheet& sheet : sheets) {
      if (sheet.ring.size() < 3) {
        a.refusal = to_string(RemovalRefusal::single_triangle_side);
        return a;
      }
      std::vector<Eigen::Vector3d> ring_positions;
      for (Index w : sheet.ring) ring_positions.push_back(map_.position(w));
      auto f = flatten_half_(map_.position(v), ring_positions);
      if (!f) {
        a.refusal = to_string(RemovalRefusal::flattening_not_simple);
        return a;
      }
      flat.push_back(std::move(*f));
    }
    // Diagonals through a node of a sheet are avoided by triangulating that sheet again, and a
    // flattening perturbed once where that is not enough (as for a closed star).
    std::vector<HoleTriangles> triangles(sheets.size());
    HolePlanning planning = plan_avoiding_nodes(v, sheets, flat, triangles, extent, a);
    if (blocked_by_a_node(a, planning)) planning = plan_on_perturbed_flattening(v, sheets, flat, triangles, extent, a, planning);
    if (planning != HolePlanning::planned) {
      a.refusal = to_string(out_of_triangulations(a, planning));
      return a;
    }
    return judge(std::move(a));
  }

  /// How planning a hole ended: with a plan in a.plan (accepted or refused), without any
  /// triangulation, or without one left after diagonals were avoided.
  enum class HolePlanning { planned, no_triangulation, no_triangulation_left };

  /// Triangulates every sheet's hole and plans the removal of v into a.plan. A diagonal that
  /// the plan finds through a vertex preimage (node_on_new_edge), along an S2 edge's preimage
  /// (edge_along_new_edge) or, once retry_folded_removals has switched it on, in a new triangle
  /// that faces against the star (fold_over: on a curved star another triangulation of the
  /// flattened polygon may not) is avoided and its sheet triangulated again, at most once per
  /// ring vertex.
  HolePlanning plan_avoiding_nodes(Index v, const std::vector<StarSheet>& sheets, const std::vector<std::vector<Eigen::Vector2d>>& flats,
                           std::vector<HoleTriangles>& triangles, PlanExtent extent, Attempt& a) const {
    std::vector<std::array<int, 3>> avoided;  // sheet, i, j
    std::size_t budget = 0;
    for (const StarSheet& sheet : sheets) budget += sheet.ring.size();
    for (std::size_t tries = 0; tries < budget; ++tries) {
      for (std::size_t g = 0; g < sheets.size(); ++g) {
        // One pointer captured: the std::function holds it in place (four references made it
        // allocate for every triangulation).
        const struct {
          const std::vector<std::array<int, 3>>& avoided;
          const std::vector<Index>& ring;
          const EditableMap& map;
          int sheet;
        } ask{avoided, sheets[g].ring, map_, static_cast<int>(g)};
        const DiagonalAllowed allowed = [c = &ask](int i, int j) {
          const std::array<int, 3> key{c->sheet, std::min(i, j), std::max(i, j)};
          return std::find(c->avoided.begin(), c->avoided.end(), key) == c->avoided.end() &&
                 !c->map.has_edge(c->ring[i], c->ring[j]);
        };
        auto t = triangulate_(flats[g], allowed);
        if (!t) return avoided.empty() ? HolePlanning::no_triangulation : HolePlanning::no_triangulation_left;
        triangles[g] = std::move(*t);
      }
      a.plan = map_.plan_vertex_removal(v, sheets, flats, triangles, extent, std::move(a.plan));
      const bool blocked = a.plan.refusal == RemovalRefusal::node_on_new_edge ||
                           a.plan.refusal == RemovalRefusal::edge_along_new_edge ||
                           (avoid_folds_ && a.plan.refusal == RemovalRefusal::fold_over);
      if (!blocked || a.plan.blocking_diagonal[0] < 0) break;
      avoided.push_back({a.plan.blocking_sheet, a.plan.blocking_diagonal[0], a.plan.blocking_diagonal[1]});
    }
    return HolePlanning::planned;
  }

  /// Why planning found no triangulation: every triangulation left after avoiding diagonals
  /// folded over is told as fold_over (the star is too curved to be replaced by flat
  /// triangles), any other end as no_triangulation.
  static RemovalRefusal out_of_triangulations(const Attempt& a, HolePlanning planning) {
    return planning == HolePlanning::no_triangulation_left && a.plan.refusal == RemovalRefusal::fold_over
               ? RemovalRefusal::fold_over
               : RemovalRefusal::no_triangulation;
  }

  /// Whether planning stopped at a degeneracy a perturbed flattening may lift: refused for a
  /// vertex preimage on a new edge, or left without a triangulation after avoiding diagonals
  /// (through preimages or along S2 edges).
  static bool blocked_by_a_node(const Attempt& a, HolePlanning planning) {
    return planning == HolePlanning::planned ? a.plan.refusal == RemovalRefusal::node_on_new_edge
                                             : planning == HolePlanning::no_triangulation_left;
  }

  /// Plans v's removal again (as plan_avoiding_nodes) on the sheets' flattenings perturbed
  /// (perturb), which then replace `flats`; judge() checks such a plan further.
  /// `before` is returned, and a.plan left as it is, if a flattening cannot be perturbed.
  HolePlanning plan_on_perturbed_flattening(Index v, const std::vector<StarSheet>& sheets,
                                            std::vector<std::vector<Eigen::Vector2d>>& flats,
                                            std::vector<HoleTriangles>& triangles, PlanExtent extent, Attempt& a,
                                            HolePlanning before) const {
    std::vector<std::vector<Eigen::Vector2d>> perturbed = flats;
    for (std::size_t g = 0; g < sheets.size(); ++g)
      if (!perturb(perturbed[g], sheets[g].ring, !sheets[g].closed)) return before;
    const HolePlanning planning = plan_avoiding_nodes(v, sheets, perturbed, triangles, extent, a);
    a.perturbed = true;
    flats = std::move(perturbed);
    return planning;
  }

  /// Whether the plan reshapes the preimage of an S2 triangle with a corner that a perturbed
  /// plan placed (it relocates a corner of such a triangle).
  bool moves_perturbed_preimage(const VertexRemovalPlan& plan) const {
    if (!any_perturbed_) return false;
    const Surface<2>& t2 = map_.target();
    for (const auto& r : plan.relocations)
      for (Index e : t2.vertex_elements(r.target_vertex))
        for (Index w : t2.element(e))
          if (perturbed_preimage_[static_cast<std::size_t>(w)]) return true;
    return false;
  }
  static constexpr double min_perturbed_shape_ratio = 1e-3;

  /// Moves each ring vertex of a flattened star (v at the origin) by a relative step of at most
  /// 1e-5, along its ray from the origin and across it, fixed per S2 vertex (golden-ratio
  /// sequences of its index), except, with keep_ends, the first and last (the ends of a feature
  /// line, which every sheet must place alike). Straight lines between ring vertices then no
  /// longer pass through v or through the nodes that a regular grid puts exactly on them. Left
  /// as it was (false) if a fan triangle would lose its orientation: then it is no flattening.
  static bool perturb(std::vector<Eigen::Vector2d>& flat, const std::vector<Index>& ring, bool keep_ends) {
    constexpr double golden = 0.6180339887498949, silver = 0.4142135623730951, spread = 1e-5;
    std::vector<Eigen::Vector2d> moved = flat;
    for (std::size_t i = 0; i < moved.size(); ++i) {
      if (keep_ends && (i == 0 || i + 1 == moved.size())) continue;
      const double u = static_cast<double>(ring[i]) * golden, w = static_cast<double>(ring[i]) * silver;
      const double radial = spread * (u - std::floor(u) - 0.5), turn = spread * (w - std::floor(w) - 0.5);
      const Eigen::Vector2d p = moved[i];
      moved[i] = (1.0 + radial) * (p + turn * Eigen::Vector2d(-p.y(), p.x()));
    }
    const std::size_t fans = keep_ends ? moved.size() - 1 : moved.size();
    for (std::size_t i = 0; i < fans; ++i) {
      const Eigen::Vector2d& a = moved[i];
      const Eigen::Vector2d& b = moved[(i + 1) % moved.size()];
      if (orient2d(Eigen::Vector2d::Zero(), a, b) <= 0) return false;
    }
    flat = std::move(moved);
    return true;
  }

  /// Refusal by the planner, the error bound, or the oracles.
  Attempt judge(Attempt a) const {
    if (!a.plan.accepted()) {
      a.refusal = to_string(a.plan.refusal);
      return a;
    }
    if (a.plan.max_node_distance > options_.max_error) {
      a.refusal = "max_error";
      return a;
    }
    // A perturbed flattening, and every later step that moves a preimage placed by one, may
    // make positive what is exactly degenerate without the perturbation (three preimages of an
    // S2 triangle on one line, which the exact tests refuse): such steps must not flatten an S2
    // triangle's preimage far below its own shape, or the map is ill-conditioned there. Checked
    // for the full plan only (a ranking bound relocates the same preimages, but late stars hold
    // thousands of them and are ranked again after every removal next to them).
    if (a.plan.extent == PlanExtent::full && (a.perturbed || moves_perturbed_preimage(a.plan)) &&
        map_.smallest_preimage_shape_ratio(a.plan) < min_perturbed_shape_ratio) {
      a.refusal = "flattened_preimage";
      return a;
    }
    a.verdict = options_.oracles.evaluate({map_, a.plan, length_scale_});
    if (a.verdict.veto) a.refusal = "oracle_veto";
    return a;
  }

  static std::uint64_t edge_key(Index a, Index b) {
    const auto [x, y] = std::minmax(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
  }

  /// After v was removed along its line, its line neighbours are each other's, joined by a
  /// feature edge.
  void join_line_neighbours(Index v) {
    const auto [left, right] = line_neighbours_[v];
    if (left == invalid_index || is_corner(v)) return;
    feature_s1_edges_.erase(edge_key(v, left));
    feature_s1_edges_.erase(edge_key(v, right));
    feature_s1_edges_.insert(edge_key(left, right));
    for (auto [end, other] : {std::pair{left, right}, std::pair{right, left}})
      for (Index& n : line_neighbours_[end])
        if (n == v) n = other;
  }

  /// Ranks v (if removable) and queues it; an older queue entry of v becomes stale. The rank is
  /// the oracles' cost of the plan's ranking bound (PlanExtent): a lower bound of the full
  /// plan's cost, since only the Hausdorff oracle looks at the nodes and it grows with them.
  /// Ranking fully would cost one full plan per ring vertex of every removal (about six).
  void rank(Index v) {
    ++stamp_[v];
    if (!map_.is_live_vertex(v) || is_corner(v)) return;
    if (estimated_) {
      // Ranked by the estimate alone (simplify_ranking_estimate.hpp): whether v can be removed
      // at all is found when it comes up. A plan kept for v is stale now.
      last_refusal_[v].clear();
      PreparedHole& hole = prepared_[v];
      if (hole.has_full_plan) give_back(std::move(*hole.full_plan));
      hole.has_full_plan = false;
      hole.sheet.ring.clear();
      const auto e = estimate_.estimate(v, line_neighbours_[v]);
      // The aspect-ratio oracle's cost (worst new minus worst old aspect ratio, at least -1e3)
      // is at least this: a star of thin triangles comes up early, as with the exact ranking.
      const double aspect = std::max(e.best_new_aspect - e.worst_star_aspect, -1e3);
      queue_.push({hausdorff_weight_ * e.distance / length_scale_ + aspect_weight_ * aspect, v, stamp_[v], true});
      return;
    }
    Attempt a = attempt(v, PlanExtent::ranking_bound);
    ++ranking_plans_;
    last_refusal_[v] = a.refusal;
    if (a.refusal.empty()) queue_.push({a.verdict.cost, v, stamp_[v], false});
    give_back(std::move(a.plan));
  }

  void run(SimplifyReport& report) {
    const Index vertex_count = map_.target().vertex_count();
    for (Index v = 0; v < vertex_count; ++v) rank(v);
    auto target_reached = [&] {
      return (options_.target_elements > 0 && map_.live_triangle_count() <= options_.target_elements) ||
             (options_.target_vertices > 0 && map_.live_vertex_count() <= options_.target_vertices);
    };
    while (!target_reached()) {
      if (queue_.empty() && !retry_folded_removals()) break;
      if (queue_.empty()) continue;
      const Entry top = queue_.top();
      queue_.pop();
      if (top.stamp != stamp_[top.vertex] || !map_.is_live_vertex(top.vertex)) continue;
      // The star may have changed around it (a new edge between two ring vertices), and it was
      // ranked by a lower bound, so the step is planned fully on the current state. Every queued
      // cost is a lower bound of its vertex's full cost, so a vertex whose full cost is not
      // above its queued cost is the cheapest of all (the order of ranking every candidate
      // fully); otherwise it goes back with its full cost.
      if (top.estimated && !confirm_estimate(top.vertex)) continue;
      Attempt a = attempt(top.vertex, PlanExtent::full);
      ++report.full_plans;
      last_refusal_[top.vertex] = a.refusal;
      if (!a.refusal.empty()) {
        ++stamp_[top.vertex];
        give_back(std::move(a.plan));
        continue;
      }
      // With the estimate ranking the queued cost is no bound: the vertex is removed if its
      // full cost is not above the next queued cost (it is still the cheapest known), otherwise
      // it goes back with its full cost, which is exact from then on.
      if (estimated_ ? a.verdict.cost > next_queued_cost() : a.verdict.cost > top.cost) {
        ++report.requeued;
        // Its full cost is above its queued cost: queue it again at the right place. Exactly,
        // without a tolerance: on flat pieces (a cube's faces) costs tie within rounding, and
        // removing a vertex whose full cost is a rounding error above the next one's changes the
        // greedy order and can leave the run stuck above its target. Planning is
        // deterministic, so a vertex queued with its full cost passes this test when popped
        // on an unchanged map.
        ++stamp_[top.vertex];
        queue_.push({a.verdict.cost, top.vertex, stamp_[top.vertex], false});
        PreparedHole& hole = prepared_[top.vertex];
        hole.stamp = stamp_[top.vertex];  // the map did not change: its hole stays, and so does the plan
        if (!hole.sheet.ring.empty()) {
          if (hole.has_full_plan) give_back(std::move(*hole.full_plan));
          if (!hole.full_plan) hole.full_plan = std::make_unique<VertexRemovalPlan>();
          *hole.full_plan = std::move(a.plan);
          hole.has_full_plan = true;
        } else {
          give_back(std::move(a.plan));
        }
        continue;
      }
      map_.apply(a.plan);
      if (a.perturbed) {
        any_perturbed_ = true;
        for (const auto& r : a.plan.relocations) perturbed_preimage_[static_cast<std::size_t>(r.target_vertex)] = 1;
      }
      options_.oracles.on_applied(map_, a.plan);
      if (estimated_) estimate_.on_applied(a.plan);
      join_line_neighbours(top.vertex);
      ++report.removed_vertices;
      if (a.plan.line_edge[0] != invalid_index) ++report.removed_along_lines;
      const std::vector<Index> ring = std::move(a.plan.ring);
      give_back(std::move(a.plan));
      for (Index w : ring) ++new_edges_[w];  // every new S1 edge joins two of these
      prepared_[top.vertex] = PreparedHole{};
      for (Index w : ring) rank(w);
      if (options_.progress && options_.progress_every > 0 && report.removed_vertices % options_.progress_every == 0)
        report_removals(report, false);
    }
    report.target_reached = target_reached();
    report.ranking_plans = ranking_plans_;
    report.requeued += requeued_;
  }

  /// Nothing is left in the queue above the target. The vertices refused because a new
  /// triangle of their hole's triangulation folded over are ranked again, and from now on such
  /// a fold makes the planner try the hole without that triangle's diagonal (plan_avoiding_nodes).
  /// Only then: it costs a triangulation and a plan per retry (+15 % instructions on the femur
  /// to 500 when it was on from the start), and runs that reach their target without it keep
  /// their maps. Once per run; false if it was used already.
  bool retry_folded_removals() {
    if (avoid_folds_ || !options_.retry_folded_removals) return false;
    avoid_folds_ = true;
    const std::string folded = to_string(RemovalRefusal::fold_over);
    const Index vertex_count = map_.target().vertex_count();
    for (Index v = 0; v < vertex_count; ++v)
      if (map_.is_live_vertex(v) && last_refusal_[v] == folded) rank(v);
    return true;
  }

  /// A vertex queued by its estimate came up: its ranking plan (whose flattening and hole the
  /// full plan then reuses) decides. False if it cannot be removed or its ranking cost is above
  /// the next queued cost; then it went back into the queue with that cost, a lower bound of the
  /// full cost like those of the exact ranking.
  bool confirm_estimate(Index v) {
    Attempt a = attempt(v, PlanExtent::ranking_bound);
    ++ranking_plans_;
    last_refusal_[v] = a.refusal;
    const bool refused = !a.refusal.empty();
    const bool above = !refused && a.verdict.cost > next_queued_cost();
    if (!refused && !above) {
      if (confirmed_.vertex != invalid_index) give_back(std::move(confirmed_));
      confirmed_ = std::move(a.plan);  // the full plan, made next, continues from it
      return true;
    }
    give_back(std::move(a.plan));
    ++stamp_[v];
    if (above) {
      ++requeued_;
      queue_.push({a.verdict.cost, v, stamp_[v], false});
      PreparedHole& hole = prepared_[v];
      if (!hole.sheet.ring.empty()) hole.stamp = stamp_[v];  // the map did not change: its hole stays
    }
    return false;
  }

  /// The "removing vertices" progress (see SimplifyOptions::progress); `finished`: the phase
  /// is over, whether or not the target was reached.
  void report_removals(const SimplifyReport& report, bool finished) const {
    std::uint64_t done = static_cast<std::uint64_t>(report.removed_vertices), total = 0;
    if (options_.target_elements > 0) {
      total = static_cast<std::uint64_t>(report.elements_before - options_.target_elements);
      done = static_cast<std::uint64_t>(std::max<Index>(0, report.elements_before - map_.live_triangle_count()));
    } else if (options_.target_vertices > 0) {
      total = static_cast<std::uint64_t>(report.vertices_before - options_.target_vertices);
    }
    if (total > 0)
      done = finished ? total : std::min(done, total);
    else if (finished)
      total = done;
    report_progress(options_.progress, "removing vertices", done, total);
  }

 private:
  /// The cost of the cheapest current queue entry (stale ones are dropped), or infinity.
  double next_queued_cost() {
    while (!queue_.empty() &&
           (queue_.top().stamp != stamp_[queue_.top().vertex] || !map_.is_live_vertex(queue_.top().vertex)))
      queue_.pop();
    return queue_.empty() ? std::numeric_limits<double>::infinity() : queue_.top().cost;
  }

  struct Entry {
    double cost;
    Index vertex;
    std::uint32_t stamp;
    bool estimated;  ///< queued by the estimate ranking, not by a plan
    bool operator>(const Entry& o) const { return cost > o.cost || (cost == o.cost && vertex > o.vertex); }
  };
  SimplifyOptions& options_;
  EditableMap map_;
  AnyStarFlattening flatten_;
  AnyStarFlattening flatten_half_;
  AnyHoleTriangulation triangulate_;
  detail::SimplifyRankingEstimate estimate_;
  bool estimated_ = false;          ///< options.ranking == "estimate"
  bool avoid_folds_ = false;        ///< fold_over refusals retried with other triangulations (retry_folded_removals)
  double hausdorff_weight_ = 0.0;   ///< the summed weight of the Hausdorff oracles, for the estimate
  double aspect_weight_ = 0.0;      ///< the summed weight of the aspect-ratio oracles, for the estimate
  double length_scale_ = 1.0;
  Index ranking_plans_ = 0;
  Index requeued_ = 0;  ///< by confirm_estimate
  std::vector<char> feature_vertex_;
  std::vector<char> corner_;  ///< feature corners: never removed
  /// Per vertex on a feature line, its two neighbours along the line in S1 (invalid if none).
  std::vector<std::array<Index, 2>> line_neighbours_;
  Index feature_edge_count_ = 0;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::string> last_refusal_;
  std::vector<PreparedHole> prepared_;  ///< per vertex, from its latest ranking
  /// Per S2 vertex: its preimage was placed by a plan on a perturbed flattening (judge()).
  std::vector<char> perturbed_preimage_;
  bool any_perturbed_ = false;
  /// The S1 edges on feature lines, by edge_key: S2's feature edges, then also the edges that
  /// removals along the lines made (join_line_neighbours).
  std::unordered_set<std::uint64_t> feature_s1_edges_;
  std::vector<std::uint32_t> new_edges_;  ///< per vertex, how many removals gave it new S1 edges (or might have)
  /// Plans no longer needed, whose buffers the next plans reuse (a plan kept for a queued vertex
  /// comes back here when the vertex is ranked again).
  std::vector<VertexRemovalPlan> spare_plans_;
  VertexRemovalPlan spare_plan() {
    if (spare_plans_.empty()) return {};
    VertexRemovalPlan plan = std::move(spare_plans_.back());
    spare_plans_.pop_back();
    return plan;
  }
  void give_back(VertexRemovalPlan plan) {
    // A few spares cover the plans of one step; more would only hold memory.
    if (spare_plans_.size() < 8) spare_plans_.push_back(std::move(plan));
  }
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
  /// The ranking plan confirm_estimate accepted, until the full plan of its vertex takes it
  /// (vertex invalid: none).
  VertexRemovalPlan confirmed_;
};

}  // namespace

SimplifyResult simplify(std::shared_ptr<const Surface<2>> fine, SimplifyOptions options) {
  const auto start = Clock::now();
  if (!fine) throw Error("simplify: no surface given");
  const Surface<2>& s = *fine;
  detail::check_simplify_options(options, s.element_count(), s.vertex_count(), "surface", "triangles");
  detail::check_no_isolated_vertices(s, "surface", "triangles");
  if (options.ranking != "exact" && options.ranking != "estimate")
    throw Error(fmt::format("simplify: unknown ranking '{}' (exact or estimate)", options.ranking));
  if (options.cut != "per-step" && options.cut != "deferred")
    throw Error(fmt::format("simplify: unknown cut '{}' (per-step or deferred)", options.cut));
  options.edit.defer_cut = options.cut == "deferred";
  if (options.oracles.empty()) options.oracles.add("hausdorff", 1.0).add("aspect-ratio", 0.05).add("normal-deviation", 0.5);

  SimplifyReport report;
  report.elements_before = s.element_count();
  report.vertices_before = s.vertex_count();
  report.oracles = options.oracles.description();
  report.flattening = options.flattening;
  report.hole_triangulation = options.hole_triangulation;
  report.ranking = options.ranking;
  report.cut = options.cut;

  Simplifier simplifier(fine, options);
  report.feature_edges = simplifier.feature_edge_count();
  report.feature_vertices = simplifier.feature_vertex_count();
  report.feature_corners = simplifier.feature_corner_count();
  simplifier.run(report);
  report.seconds_simplify = seconds_since(start);
  simplifier.report_removals(report, true);

  for (Index v = 0; v < s.vertex_count(); ++v) {
    if (!simplifier.map().is_live_vertex(v) || simplifier.is_corner(v)) continue;
    const std::string& why = simplifier.last_refusal()[v];
    if (why.empty()) continue;  // still removable: the target stopped the run
    ++report.skipped_by_reason[why];
    ++report.skipped_vertices;
  }

  const auto finalize_start = Clock::now();
  report_progress(options.progress, "finalize", 0, 1);
  std::optional<PlMap<2>> traced;
  try {
    // The deferred cut refuses steps the per-step cut makes (straight_fold): a run it stopped
    // above its target is redone per step too.
    if (options.edit.defer_cut && !report.target_reached && (options.target_elements > 0 || options.target_vertices > 0))
      throw DeferredCutFailure(fmt::format("deferred cut: the run stopped at {} triangles, above its target",
                                           simplifier.map().live_triangle_count()));
    traced = simplifier.map().to_map(options.builder);
  } catch (const DeferredCutFailure& failure) {
    // The deferred cut's traced graph is not a valid parametrization: redo the run with the
    // per-step cut, whose every step is checked.
    SimplifyOptions again = options;
    again.cut = "per-step";
    again.edit.defer_cut = false;
    // The oracles keep state about the map they judged (shared by copies of the options): the
    // ones known by name start afresh; a custom oracle is handed over as it is.
    again.oracles = WeightedOracles{};
    for (const auto& [name, weight] : options.oracles.named_weights()) {
      const auto names = error_oracle_names();
      if (std::find(names.begin(), names.end(), name) != names.end()) again.oracles.add(name, weight);
    }
    if (again.oracles.named_weights().size() != options.oracles.named_weights().size()) again.oracles = options.oracles;
    SimplifyResult result = simplify(std::move(fine), std::move(again));
    result.report.cut = "deferred";
    result.report.cut_fell_back = true;
    result.report.cut_failure = failure.what();
    result.report.seconds_total = seconds_since(start);
    return result;
  }
  PlMap<2> map = std::move(*traced);
  report_progress(options.progress, "finalize", 1, 1);
  report.seconds_finalize = seconds_since(finalize_start);
  detail::report_simplified_map(map, s, report);
  report.seconds_total = seconds_since(start);
  return {std::move(map), std::move(report)};
}

}  // namespace plmap
