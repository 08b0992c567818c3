// Normal projection, phase 2: vertex preimages (projection_vertex_preimages.hpp).

#include "projection_vertex_preimages.hpp"

#include "curve_solution_side.hpp"
#include "preimage_rank_floor.hpp"
#include "projection_seeds.hpp"
#include "simplex_distance.hpp"
#include "vertex_star_probe.hpp"

#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace plmap::projection {

namespace {

/// The searches for the preimages of S2 vertices.
template <int d, class Solver>
class VertexPreimageSearch {
 public:
  VertexPreimageSearch(const ProjectionContext<d>& ctx, const Solver& solver, SeedWalks walks)
      : ctx_(ctx), solver_(solver),
        may_skip_walks_(walks == SeedWalks::until_no_rival_left && ctx.s1_boxes->has_tree()),
        may_skip_rootless_steps_(d == 1 && walks == SeedWalks::until_no_rival_left) {
    accept_.solver_tolerance = solver.options.relative_tolerance;
    accept_.inside_tolerance = ctx.options.search_limits.inside_tolerance;
    accept_.allow_negative_distance = ctx.options.allow_negative_distance;
    longest_edge_ = ctx.s1.max_edge_length() * (1.0 + 1e-12);
    coordinate_magnitude_ =
        std::max(ctx.s1.bounding_box_min().cwiseAbs().maxCoeff(), ctx.s1.bounding_box_max().cwiseAbs().maxCoeff());
  }

  /// A plain flag and value rather than std::optional, on which GCC 12 warns falsely
  /// (maybe-uninitialized) for Eigen members.
  struct SearchOffset {
    bool valid = false;
    WorldPoint<d> value = WorldPoint<d>::Zero();
  };

  /// What the walks from one set of seeds found.
  struct SeededSearch {
    /// The admissible solution of least rank, if any.
    std::optional<SurfacePoint<d>> preimage;
    /// A walk stopped because the solver did not converge (more seeds may then help).
    bool solver_failed = false;
    /// The preimage's element sees the S2 vertex's star (vertex_star_probe.hpp); if not, it
    /// may lie on the far side of a seam of S1.
    bool sees_star = true;
  };

  /// The preimage of S2 vertex q, seeded next to q moved by the chunk's previous offset (if
  /// any), else at q itself.
  std::optional<SurfacePoint<d>> find_vertex_preimage(Index q, const SearchOffset& offset,
                                                      NearestElements<d>& nearest) const {
    if (offset.valid) {
      SeededSearch moved = search_from_seeds(q, ctx_.s2.vertex(q) - offset.value, ctx_.seed_count, &nearest);
      if (moved.preimage && moved.sees_star) return moved.preimage;
    }
    return find_vertex_preimage(q);
  }

  std::optional<SurfacePoint<d>> find_vertex_preimage(Index q) const {
    SeededSearch search = search_from_seeds(q, ctx_.s2.vertex(q), ctx_.seed_count, nullptr);
    // The elements nearest to q may all be tangential to the directions (eq. 3 is singular there),
    // e.g. the horizontal sheets of a T-junction when the vertical sheet is the one that sees S2:
    // their walks end at once, before reaching the element that holds the preimage. Only then is
    // the search repeated from more seeds (search_limits.retry_seeds), so the usual case costs
    // nothing extra.
    if (!search.preimage && search.solver_failed && ctx_.seed_count < ctx_.retry_seed_count)
      search = search_from_seeds(q, ctx_.s2.vertex(q), ctx_.retry_seed_count, nullptr);
    // A preimage on the far side of a seam of S1 (its element does not see q's star), found
    // where q lies on S1: the near side's elements through q may be long ones whose centroids
    // are not among the nearest (CGAL's oblong-shuffled.off, a lid cut free on three sides),
    // and no walk crosses a seam. The walks are repeated from every element through the preimage
    // found, on either side; of equal ranks the one that sees the star wins.
    if (search.preimage && !search.sees_star) {
      const WorldPoint<d> at = ctx_.s1.world_position(search.preimage->element, search.preimage->local);
      SeedElements through;
      const int count = elements_through(at, through);
      if (count > 0) {
        const SeededSearch again = walk_to_preimage(q, through, count);
        if (again.preimage && again.sees_star) search = again;
      }
    }
    return search.preimage;
  }

  /// The S1 elements (up to max_search_seeds) whose closure contains x, up to the snapping
  /// tolerance of their size; their centroids lie within the index's radius of x.
  int elements_through(const WorldPoint<d>& x, SeedElements& out) const {
    int count = 0;
    auto consider = [&](Index t) {
      if (count < max_search_seeds &&
          element_distance(x, t) <= ctx_.options.snap_tolerance * longest_edge<d>(corners_of(t)))
        out[count++] = static_cast<std::uint32_t>(t);
    };
    if (ctx_.s1_boxes->has_tree()) {
      ctx_.s1_boxes->visit_near(x, ctx_.options.snap_tolerance * longest_edge_, consider);
    } else {
      for (Index t : ctx_.s1_index->within(x, ctx_.s1_index->radius * (1.0 + 1e-12))) consider(t);
    }
    return count;
  }

  /// Eq. (3) for S2 vertex q on walks across S1 that start at the `seed_count` elements nearest
  /// to `seed_point` (found with `nearest` for the moved seed points, which follow each other
  /// closely, else with the kd-tree).
  SeededSearch search_from_seeds(Index q, const WorldPoint<d>& seed_point, int seed_count,
                                 NearestElements<d>* nearest) const {
    SeedElements seeds;
    int count = nearest_seeds(*ctx_.s1_index, nearest, seed_point, seed_count, seeds);
    count = add_long_elements_through(seed_point, seeds, count);
    return walk_to_preimage(q, seeds, count);
  }

  /// The nearest centroids miss an element that passes right by x when its centroid lies
  /// farther than theirs (a long element among short ones: the steep sides of a zigzag curve),
  /// and the walks from the seeds stop at the first element that holds a solution, which may rank
  /// worse than the one on the missed element (an S2 vertex on S1 then takes a preimage off
  /// itself). Such elements are added as seeds, nearest centroid first, up to max_search_seeds:
  /// those that lie nearer to x than the seed with the nearest centroid itself (the element
  /// itself, not its centroid, which lies farther). The test is the distance to the element, not
  /// to its bounding box: a box depends on the coordinate axes, so with boxes a rigid motion of
  /// both surfaces changed which elements were added and, next to a fold of the projection, which
  /// of two sheets an S2 vertex took (ProjectProperties.OffsetHeightFieldsWithAveragedNormals);
  /// the box index only names the candidates. An element through x lies at distance 0, below the
  /// distance of any seed that does not pass through x, so the zigzag's long sides are still
  /// added; an S2 vertex a gap above S1, whose nearest centroid lies about the gap away, gets no
  /// walks from all the elements around it (with the centroid as the bound a third of the
  /// vertices of the planes and real-mesh pairs did, and found nothing new). Every element within
  /// the bound has its centroid within it plus the largest centroid-to-corner distance, and on
  /// meshes of even element size those are seeds already, so this adds none and costs no query.
  int add_long_elements_through(const WorldPoint<d>& x, SeedElements& seeds, int count) const {
    if (count == 0 || count >= max_search_seeds) return count;
    double nearest_centroid = std::numeric_limits<double>::infinity(), farthest = 0.0;
    std::uint32_t nearest_seed = seeds[0];
    for (int i = 0; i < count; ++i) {
      const double squared = ctx_.s1_index->squared_distance(x, seeds[i]);
      if (squared < nearest_centroid) {
        nearest_centroid = squared;
        nearest_seed = seeds[i];
      }
      farthest = std::max(farthest, squared);
    }
    const double bound = element_distance(x, static_cast<Index>(nearest_seed));
    // No box lies nearer than 0 (x on the nearest seed: the usual case of a map of a surface onto
    // itself). The seeds are the nearest centroids: if they reach beyond the candidates'
    // centroids, or are all there are, every candidate is a seed already (the usual case, at the
    // cost of no tree query).
    if (!(bound > 0.0) || count >= ctx_.s1_index->size() || std::sqrt(farthest) > bound + ctx_.s1_index->radius)
      return count;
    // The candidates are the elements whose centroid lies within bound + radius of x (every
    // element within `bound` has its centroid there) and that lie nearer than `bound`; their
    // boxes do too, so the box index names a superset of them without the wide centroid query
    // (the cheap box test first, the element's distance decides).
    const double reach = bound + ctx_.s1_index->radius;
    std::vector<std::pair<double, Index>> added;
    auto consider = [&](Index t) {
      if (std::find(seeds.begin(), seeds.begin() + count, static_cast<std::uint32_t>(t)) != seeds.begin() + count)
        return;
      if (box_distance(x, t) < bound && element_distance(x, t) < bound)
        added.emplace_back(ctx_.s1_index->squared_distance(x, static_cast<std::uint32_t>(t)), t);
    };
    if (ctx_.s1_boxes->has_tree()) {
      ctx_.s1_boxes->visit_near(x, bound, [&](Index t) {
        if (ctx_.s1_index->squared_distance(x, static_cast<std::uint32_t>(t)) < reach * reach) consider(t);
      });
    } else {
      for (Index t : ctx_.s1_index->within(x, reach)) consider(t);
    }
    std::sort(added.begin(), added.end());
    for (const auto& [unused, t] : added) {
      if (count == max_search_seeds) break;
      seeds[count++] = static_cast<std::uint32_t>(t);
    }
    return count;
  }

  /// Distance from x to S1 element t.
  double element_distance(const WorldPoint<d>& x, Index t) const {
    std::array<WorldPoint<d>, d + 1> corners;
    for (int k = 0; k <= d; ++k) corners[k] = ctx_.s1.corner(t, k);
    return simplex_distance<d>(x, corners);
  }

  /// Distance from x to the bounding box of S1 element t (0 inside it).
  double box_distance(const WorldPoint<d>& x, Index t) const {
    return ElementBoxIndex<d>::box_distance(x, ctx_.s1_boxes->box(t));
  }

  std::array<WorldPoint<d>, d + 1> corners_of(Index t) const {
    std::array<WorldPoint<d>, d + 1> corners;
    for (int k = 0; k <= d; ++k) corners[k] = ctx_.s1.corner(t, k);
    return corners;
  }

  /// Beyond this many times the best element's longest edge from q, the walks are not skipped.
  static constexpr double rival_gap_limit = 4.0;

  /// The elements solved so far by the walks for one S2 vertex (the first 64 of them).
  struct SolvedElements {
    std::array<Index, 64> elements;
    int count = 0;
    bool contains(Index t) const { return std::find(elements.begin(), elements.begin() + count, t) != elements.begin() + count; }
    void add(Index t) {
      if (count < 64) elements[count++] = t;
    }
  };

  /// The elements not yet solved on which a walk could still accept a preimage of lower rank
  /// than the best one found (their rank floor, preimage_rank_floor.hpp, lies below it).
  struct Rivals {
    static constexpr int capacity = 16;
    std::array<std::pair<double, Index>, capacity> floor_and_element;
    int count = 0;
    bool collected = false;
    bool too_many = false;  ///< more than `capacity`: the walks go on as before
  };

  /// Whether no element is left on which a walk could find a preimage of rank below
  /// `best_rank`. Then the walks still to come cannot change the answer: an element not solved
  /// yet cannot beat it, and one solved already gives the same solution again (same element,
  /// same target), which did not beat it then. The rivals are collected once, at the first
  /// preimage found, and only filtered afterwards (a lower rank has fewer rivals, and solved
  /// elements stay solved).
  bool no_rival_left(const WorldPoint<d>& q, double best_rank, Index best_element, const SolvedElements& solved,
                     Rivals& rivals) const {
    if (!(best_rank > 0.0)) return true;  // no rank lies below 0
    if (rivals.too_many) return false;
    if (!rivals.collected) {
      rivals.collected = true;
      // Every element whose box lies within the rank of q is a candidate, and where q lies many
      // element sizes from S1 those are many (they pass by q at about that distance): proving
      // the walks skippable would cost more than walking them.
      if (best_rank > rival_gap_limit * longest_edge<d>(corners_of(best_element))) {
        rivals.too_many = true;
        return false;
      }
      const double radius = rival_search_radius<d>(q, best_rank, longest_edge_, coordinate_magnitude_, accept_);
      ctx_.s1_boxes->visit_near(q, radius, [&](Index t) {
        if (rivals.too_many || solved.contains(t)) return;
        const double floor = preimage_rank_floor<d>(q, corners_of(t), accept_);
        if (!(floor < best_rank)) return;
        if (rivals.count == Rivals::capacity) {
          rivals.too_many = true;
          return;
        }
        rivals.floor_and_element[rivals.count++] = {floor, t};
      });
      if (rivals.too_many) return false;
    }
    int kept = 0;
    for (int i = 0; i < rivals.count; ++i) {
      const auto [floor, t] = rivals.floor_and_element[i];
      if (floor < best_rank && !solved.contains(t)) rivals.floor_and_element[kept++] = {floor, t};
    }
    rivals.count = kept;
    return kept == 0;
  }

  /// Eq. (3) for S2 vertex q on walks across S1 from the first `count` of `seeds`: the solution
  /// of least rank among those that pass every check, or nothing. The walks stop early when no
  /// later walk can change that (no_rival_left), unless all of them were asked for.
  SeededSearch walk_to_preimage(Index q, const SeedElements& seeds, int count) const {
    const WorldPoint<d>& target = ctx_.s2.vertex(q);
    std::optional<SurfacePoint<d>> best;
    double best_rank = std::numeric_limits<double>::infinity();
    // Whether the best one lies on the sheet of S1 that sees q's star (vertex_star_probe.hpp):
    // of two preimages of equal rank (within the snapping tolerance of their elements' size, as
    // at a seam), one that does beats one that does not. Walks are skipped only after one that
    // does: a tie may still come.
    // Asked only when needed (a tie, or before walks are skipped): -1 not yet known.
    int best_sees_star = -1;
    double best_tie_margin = 0.0, best_mu = 0.0;
    const auto sees_star = [&] {
      if (best_sees_star < 0)
        best_sees_star = probe_sees_star(ctx_, best->element, best->local, best_mu, q) ? 1 : 0;
      return best_sees_star == 1;
    };
    SolvedElements solved;
    Rivals rivals;
    long long calls = 0, failures = 0;
    for (int s = 0; s < count; ++s) {
      if (may_skip_walks_ && best && no_rival_left(target, best_rank, best->element, solved, rivals) && sees_star())
        break;
      Index t = static_cast<Index>(seeds[s]);
      for (int step = 0; step < ctx_.options.search_limits.seed_walk_steps && t != invalid_index; ++step) {
        if (solved.contains(t)) break;  // walked from here already
        solved.add(t);
        const VertexProjectionSystem<d> sys = ctx_.element_system(t, target);
        if (best && rootless_step_ends_walk(t, sys, solved)) break;
        ++calls;
        const auto r = solver_.solve(sys, sys.initial_guess());
        if (!r.converged) {
          ++failures;
          break;
        }
        const LocalPoint<d> xi = r.x.template head<d>();
        const Barycentric<d> b = barycentric_from_local<d>(xi);
        int worst = 0;
        for (int k = 1; k <= d; ++k)
          if (b(k) < b(worst)) worst = k;
        if (b(worst) >= -ctx_.options.search_limits.inside_tolerance) {
          const double mu = r.x(d);
          WorldPoint<d> direction = sys.directions[0];
          for (int k = 0; k < d; ++k) direction += xi(k) * (sys.directions[k + 1] - sys.directions[0]);
          const double rank = ctx_.rank(mu);
          if (ctx_.distance_ok(mu, sys.scale()) && (ctx_.s2_vertex_normals.empty() || ctx_.normal_ok(direction, ctx_.s2_vertex_normals[q])) &&
              rank < best_rank + best_tie_margin && ctx_.unfolded_in(t, xi, mu)) {
            Barycentric<d> bc = b.cwiseMax(0.0);
            bc /= bc.sum();
            const LocalPoint<d> local = local_from_barycentric<d>(bc);
            int candidate_sees_star = -1;
            bool better = rank < best_rank;
            if (best && rank >= best_rank - best_tie_margin) {  // a tie: the side of q's star decides
              candidate_sees_star = probe_sees_star(ctx_, t, local, mu, q) ? 1 : 0;
              better = candidate_sees_star != int(sees_star()) ? candidate_sees_star == 1 : rank < best_rank;
            }
            if (better) {
              best_rank = rank;
              best_mu = mu;
              best = SurfacePoint<d>{t, local};
              best_sees_star = candidate_sees_star;
              best_tie_margin = ctx_.options.snap_tolerance * longest_edge<d>(corners_of(t));
            }
          }
          break;
        }
        t = element_across(ctx_.s1, t, worst);
      }
    }
    ctx_.solver_calls += calls;
    ctx_.solver_failures += failures;
    return SeededSearch{best, failures > 0, !best || sees_star()};
  }

  /// Whether a curve's walk step on segment t can be decided without solving: no solution of
  /// eq. (3) lies on t (so none would be accepted), they all lie to one side
  /// (curve_solution_side.hpp), and the segment on that side, where the walk would go on, is
  /// solved already or missing. Then the walk ends here, as it would after the solve. Asked only
  /// once a preimage is known: before, a failed solve matters (it calls for more seeds), and
  /// the closed form does not say whether the solver would fail.
  bool rootless_step_ends_walk(Index t, const VertexProjectionSystem<d>& sys, const SolvedElements& solved) const {
    if constexpr (d == 1) {
      if (!may_skip_rootless_steps_) return false;
      const int side = curve_solution_side(sys.corners[0], sys.corners[1], sys.directions[0], sys.directions[1],
                                           sys.target, accept_.inside_tolerance + rootless_margin);
      if (side == 0) return false;
      // beyond corner 1 (xi > 1) the walk crosses the facet opposite corner 0, and vice versa
      const Index next = element_across(ctx_.s1, t, side > 0 ? 0 : 1);
      return next == invalid_index || solved.contains(next);
    } else {
      (void)t, (void)sys, (void)solved;
      return false;
    }
  }

  /// How far (in segment lengths) beyond the accepted range a solution must lie for a curve's
  /// walk step to be decided without solving: far above a converged solver's error.
  static constexpr double rootless_margin = 1e-6;

  /// Whether the rays from the corners of S1 element t all hit S2 and their hits span a simplex
  /// of the element's orientation (seen along the mean direction). Preimages found by the second
  /// search must pass this: where rays have crossed (beyond a focal line of the field, which a
  /// twisted discrete field can hide from the focal test, whose polynomial then has no real
  /// root) the hits are mirrored, and such an element does not see S2 as a sheet.
  bool rays_keep_orientation(Index t, const projection::PointCloud<d + 1>& hits,
                             const std::vector<Index>& hit_id) const {
    std::array<WorldPoint<d>, d + 1> c, h;
    WorldPoint<d> direction = WorldPoint<d>::Zero();
    for (int k = 0; k <= d; ++k) {
      const Index v = ctx_.s1.element(t)[k];
      if (hit_id[v] == invalid_index) return false;
      c[k] = ctx_.s1.vertex(v);
      h[k] = hits.points[hit_id[v]];
      direction += ctx_.vertex_directions[v];
    }
    const auto side = [&](const std::array<WorldPoint<d>, d + 1>& p) {
      if constexpr (d == 2)
        return (p[1] - p[0]).cross(p[2] - p[0]).dot(direction);
      else
        return (p[1] - p[0]).x() * direction.y() - (p[1] - p[0]).y() * direction.x();
    };
    return side(c) * side(h) > 0.0;
  }

  /// The second search, for the S2 vertices that find_vertex_preimage left without a preimage;
  /// returns how many it maps. The first search walks from the S1 elements whose centroids lie
  /// nearest to q, and those can all lie on a sheet of S1 that is nearer to S2 but does not
  /// reach q (a body above a wider one: the upper body's elements are the nearest to every S2
  /// vertex above both). The rays know better: an S1 vertex whose ray hits S2 next to q lies on
  /// a sheet that sees q, so here the walks start from the stars of the S1 vertices with the
  /// hits nearest to q. A hit farther from q than the largest distance between the hits of two
  /// corners of an element around its vertex (with a margin) cannot belong to an element holding
  /// q's preimage and is not tried, so S2 vertices far outside S1's shadow cost one tree query.
  Index find_remaining_preimages_from_hits(const std::vector<std::optional<SurfacePoint<d>>>& hit,
                                           std::vector<std::optional<SurfacePoint<d>>>& preimage) {
    std::vector<Index> missing;
    for (Index q = 0; q < ctx_.s2.vertex_count(); ++q)
      if (!preimage[q] && !ctx_.s2.vertex_elements(q).empty()) missing.push_back(q);
    if (missing.empty()) return 0;
    // the hits as a point cloud, and the S1 vertex of each
    projection::PointCloud<d + 1> cloud;
    std::vector<Index> hit_vertex, cloud_id(ctx_.s1.vertex_count(), invalid_index);
    for (Index v = 0; v < ctx_.s1.vertex_count(); ++v) {
      if (!hit[v]) continue;
      cloud_id[v] = static_cast<Index>(cloud.points.size());
      cloud.points.push_back(ctx_.s2.world_position(hit[v]->element, hit[v]->local));
      hit_vertex.push_back(v);
    }
    if (cloud.points.empty()) return 0;
    // reach[i]: 1.5 times the largest distance between the hits of two corners of an element
    // around the S1 vertex of hit i (a local bound: grazing rays elsewhere do not widen it)
    std::vector<double> reach(cloud.points.size(), 0.0);
    for (Index t = 0; t < ctx_.s1.element_count(); ++t) {
      const auto corners = ctx_.s1.element(t);
      double diameter = 0.0;
      for (int a = 0; a <= d; ++a)
        for (int b = a + 1; b <= d; ++b) {
          const Index ia = cloud_id[corners[a]], ib = cloud_id[corners[b]];
          if (ia != invalid_index && ib != invalid_index)
            diameter = std::max(diameter, (cloud.points[ia] - cloud.points[ib]).norm());
        }
      for (Index v : corners)
        if (cloud_id[v] != invalid_index)
          reach[cloud_id[v]] = std::max(reach[cloud_id[v]], ctx_.options.search_limits.second_search_reach * diameter);
    }
    const projection::KdTree<d + 1> tree(d + 1, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<std::optional<SurfacePoint<d>>> found(missing.size());
    parallel_for_chunks(missing.size(), search_chunk, ctx_.threads, [&](Index begin, Index end) {
      const int nearest_hits = ctx_.options.search_limits.second_search_hits;
      for (Index i = begin; i < end; ++i) {
        const Index q = missing[i];
        SeedElements ids;
        std::array<double, max_search_seeds> squared;
        const int n = static_cast<int>(tree.knnSearch(ctx_.s2.vertex(q).data(), nearest_hits, ids.data(), squared.data()));
        SeedElements seeds;
        int count = 0;
        for (int j = 0; j < n; ++j) {
          if (!(squared[j] <= reach[ids[j]] * reach[ids[j]])) continue;
          for (Index t : ctx_.s1.vertex_elements(hit_vertex[ids[j]]))
            if (count < max_search_seeds && std::find(seeds.begin(), seeds.begin() + count, t) == seeds.begin() + count)
              seeds[count++] = static_cast<std::uint32_t>(t);
        }
        if (count == 0) continue;
        found[i] = walk_to_preimage(q, seeds, count).preimage;
        if (found[i] && !rays_keep_orientation(found[i]->element, cloud, cloud_id)) found[i].reset();
      }
    });
    Index mapped = 0;
    for (std::size_t i = 0; i < missing.size(); ++i)
      if (found[i]) {
        preimage[missing[i]] = found[i];
        ++mapped;
      }
    return mapped;
  }

 private:
  const ProjectionContext<d>& ctx_;
  const Solver& solver_;
  /// Whether walks are skipped when they cannot change the answer (no_rival_left; needs the box
  /// hierarchy, which surfaces of even element sizes do not build).
  bool may_skip_walks_;
  /// Whether a curve's walk steps that cannot find anything are decided without a solve
  /// (rootless_step_ends_walk).
  bool may_skip_rootless_steps_;
  PreimageAcceptance accept_;
  /// S1's longest edge (slightly enlarged) and largest coordinate: the margins of the rivals' search.
  double longest_edge_ = 0.0, coordinate_magnitude_ = 0.0;
};

}  // namespace

template <int d, class Solver>
VertexPreimages<d> find_vertex_preimages(const ProjectionContext<d>& ctx, const Solver& solver,
                                         const std::vector<std::optional<SurfacePoint<d>>>& ray_hits, SeedWalks walks) {
  using Search = VertexPreimageSearch<d, Solver>;
  Search search(ctx, solver, walks);
  VertexPreimages<d> result;
  auto& preimage = result.preimage;
  assign_on_huge_pages(preimage, static_cast<std::size_t>(ctx.s2.vertex_count()), {}, ctx.threads);
  parallel_for_chunks(ctx.s2.vertex_count(), search_chunk, ctx.threads, [&](Index begin, Index end) {
    typename Search::SearchOffset offset;  // target minus preimage of the previous vertex found
    NearestElements<d> nearest(*ctx.s1_index);
    for (Index q = begin; q < end; ++q) {
      // an isolated S2 vertex (no element) is not part of S2: it needs no preimage
      if (ctx.s2.vertex_elements(q).empty()) continue;
      preimage[q] = search.find_vertex_preimage(q, offset, nearest);
      offset.valid = preimage[q].has_value();
      if (offset.valid)
        offset.value = ctx.s2.vertex(q) - ctx.s1.world_position(preimage[q]->element, preimage[q]->local);
    }
  });
  result.found_by_ray_hits = search.find_remaining_preimages_from_hits(ray_hits, preimage);
  return result;
}

#define PLMAP_VERTEX_PREIMAGES(d, Solver)                                                           \
  template VertexPreimages<d> find_vertex_preimages<d, Solver>(const ProjectionContext<d>&, const Solver&, \
                                                               const std::vector<std::optional<SurfacePoint<d>>>&, SeedWalks);
PLMAP_VERTEX_PREIMAGES(1, DampedNewtonSolver)
PLMAP_VERTEX_PREIMAGES(2, DampedNewtonSolver)
PLMAP_VERTEX_PREIMAGES(1, CeresTinySolver)
PLMAP_VERTEX_PREIMAGES(2, CeresTinySolver)
#undef PLMAP_VERTEX_PREIMAGES

}  // namespace plmap::projection
