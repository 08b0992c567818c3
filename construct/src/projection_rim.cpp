// Normal projection, phase 5: the rim of D where S2 leaves the admissible band of distances
// (ProjectionOptions::end_on_rim; projection_insertion.hpp, insert_rim).
//
// A walk stops where its S2 edge leaves the band: with the default distance rules where it passes
// behind S1 (mu < 0), with a distance limit m also where it goes beyond m (and with negative
// distances allowed, below -m). There the projection really ends on the curve where the rays'
// distance to S2 equals the bound. Over S1 element t the points at distance mu along the rays
// form a flat triangle, t's corners moved by mu along their directions (rim_geometry.hpp), and
// a point of it has the same local coordinates as the point of t it comes from; for mu = 0 it is
// t itself and Xi is the identity on the curve. So the curve is the union of the segments in
// which these triangles and S2 triangles intersect. The pieces that stopped there end at rim
// nodes where their S2 edges pierce such a triangle (planned by the walks, made by
// insert_planned_edge). From those, the curve is traced pair by pair: for an S1 element t and an
// S2 triangle A whose level-mu triangle t' meets A, the segment t' ∩ A runs between two of the
// points where an edge of A pierces t' (a rim node inside t, image on that S2 edge, continued in
// the S2 triangle across that edge) or an edge of t' pierces A (a rim node on that S1 edge, image
// inside A, continued in the S1 element across that edge), and becomes a rim edge. The faces on
// D's side of the rim then map into one S2 triangle and become regions; those beyond it reach S1
// corners without a node (their rays meet S2 outside the band) and stay out.

#include "projection_insertion.hpp"
#include "nearer_sheet.hpp"
#include "rim_geometry.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/snapping.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace plmap::projection {

namespace {

/// Segments judged per chunk on the projection's threads: a judgement takes about 2 µs (the
/// bones pair: 3,800 segments in 9 ms on one thread), a chunk of 64 about 0.1 ms.
constexpr std::size_t rim_judging_chunk = 64;

/// One end of the segment in which an S1 element and an S2 triangle meet.
struct RimEnd {
  bool on_target_edge = false;  // true: an S2 edge pierces the S1 element; false: an S1 edge pierces the S2 triangle
  Index edge = invalid_index;   // that S2 or S1 edge
  double parameter = 0.0;       // along it, from its smaller-index vertex
  LocalPoint<2> local;          // on the S1 element (on_target_edge) or on the S2 triangle
};

std::array<WorldPoint<2>, 3> corners_of(const Surface<2>& s, Index t) {
  return {s.corner(t, 0), s.corner(t, 1), s.corner(t, 2)};
}

/// The ends of the segment t' ∩ a (t' the level set at distance mu of S1 element t's rays, S2
/// triangle a): exactly two, each strictly inside its triangle and edge, or none (no
/// intersection, or a degenerate one).
template <class Context>
int rim_segment(const Context& ctx, double mu, Index t, Index a, std::array<RimEnd, 2>& ends) {
  const Surface<2>& s1 = ctx.s1;
  const Surface<2>& s2 = ctx.s2;
  int count = 0;
  auto add = [&](const RimEnd& end) {
    if (count < 2) ends[count] = end;
    ++count;
  };
  const auto t_corners = ctx.corners_at_distance(t, mu), a_corners = corners_of(s2, a);
  auto moved = [&](Index v) -> WorldPoint<2> { return s1.vertex(v) + mu * ctx.vertex_directions[v]; };
  for (int k = 0; k < 3; ++k) {
    const Index e = s2.element_edge(a, k);
    const auto ev = s2.edge_vertices(e);
    const auto p = segment_through_triangle(s2.vertex(ev[0]), s2.vertex(ev[1]), t_corners);
    if (!p) continue;
    if (!strictly_inside(p->barycentric, rim_margin) || !(p->s > rim_margin && p->s < 1.0 - rim_margin)) {
      if (p->barycentric[0] >= -rim_margin && p->barycentric[1] >= -rim_margin && p->barycentric[2] >= -rim_margin &&
          p->s >= -rim_margin && p->s <= 1.0 + rim_margin)
        return 0;  // on a side or at an end: degenerate
      continue;
    }
    add({true, e, p->s, LocalPoint<2>(p->barycentric[1], p->barycentric[2])});
  }
  for (int k = 0; k < 3; ++k) {
    const Index e = s1.element_edge(t, k);
    const auto ev = s1.edge_vertices(e);
    const auto p = segment_through_triangle(moved(ev[0]), moved(ev[1]), a_corners);
    if (!p) continue;
    if (!strictly_inside(p->barycentric, rim_margin) || !(p->s > rim_margin && p->s < 1.0 - rim_margin)) {
      if (p->barycentric[0] >= -rim_margin && p->barycentric[1] >= -rim_margin && p->barycentric[2] >= -rim_margin &&
          p->s >= -rim_margin && p->s <= 1.0 + rim_margin)
        return 0;
      continue;
    }
    add({false, e, p->s, LocalPoint<2>(p->barycentric[1], p->barycentric[2])});
  }
  return count == 2 ? 2 : 0;
}

/// Whether no ray of S1 element t meets a focal point of t's direction field before it reaches
/// the plane of S2 triangle a, over the part of t whose distance to that plane lies in the
/// admissible band (for mu = 0: in front of the plane). The faces on D's side of the rim become
/// regions, and the walks and the ray check accept no point beyond a focal point of its element
/// (walk_acceptance.hpp); a rim next to a fold would claim such points.
/// Where the element's focal-free distance (a bound for all of it) covers the corners' distances
/// to the plane that decides; else the rays are tested on a grid of 153 points (spacing 1/16 of
/// the element): tests at the corners and half-way to the rim alone let folded points through
/// on the bones pair.
template <class Context>
bool rays_unfolded_in_front(const Context& ctx, Index t, Index a) {
  const auto tri = corners_of(ctx.s2, a);
  const WorldPoint<2> normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
  auto distance_along_ray = [&](const LocalPoint<2>& xi) -> std::optional<double> {
    const Barycentric<2> b = barycentric_from_local<2>(xi);
    WorldPoint<2> nu = WorldPoint<2>::Zero();
    for (int k = 0; k < 3; ++k) nu += b(k) * ctx.vertex_directions[ctx.s1.element(t)[k]];
    const double along = normal.dot(nu);
    if (!(std::abs(along) > 1e-12 * normal.norm() * nu.norm())) return std::nullopt;
    return normal.dot(tri[0] - ctx.s1.world_position(t, xi)) / along;
  };
  // the band of admissible distances (the bounds of ProjectionContext::rim_level)
  const double lower = ctx.options.allow_negative_distance ? -ctx.distance_limit : 0.0;
  const double upper = ctx.distance_limit;
  double farthest = 0.0;
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> mu = distance_along_ray(reference_corner<2>(k));
    if (!mu) return false;
    farthest = std::max(farthest, std::abs(std::clamp(*mu, lower, upper)));
  }
  if (farthest <= ctx.focal_free_reach[t]) return true;
  constexpr int steps = 16;
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; i + j <= steps; ++j) {
      const LocalPoint<2> xi(double(i) / steps, double(j) / steps);
      const std::optional<double> mu = distance_along_ray(xi);
      if (mu && *mu != 0.0 && *mu >= lower && *mu <= upper && !ctx.unfolded_in(t, xi, *mu)) return false;
    }
  return true;
}

/// The local coordinates on S1 element t of one end of a rim segment.
template <class Context>
LocalPoint<2> end_on_element(const Context& ctx, Index t, const RimEnd& end) {
  return end.on_target_edge ? end.local : local_on_edge_of(ctx.s1, t, end.edge, end.parameter);
}

/// The other element at an edge with two, or invalid_index.
template <class Incidences>
Index other_element(const Incidences& incidences, Index t) {
  if (incidences.size() != 2) return invalid_index;
  return incidences[0].element == t ? incidences[1].element : incidences[0].element;
}

/// A segment of the rim: S1 element, S2 triangle, level, and its two ends.
struct TracedRimSegment {
  Index element, target;
  int level;
  std::array<RimEnd, 2> ends;
};

/// The rim's segments from the pairs `pending` (S1 element, S2 triangle, level; taken from the
/// back) on, in the order the tracing meets them: from each segment on to the pairs across its
/// ends (the S2 triangle across an S2 edge, the S1 element across an S1 edge), each pair once
/// (first_visit(element, triangle, level) is true the first time it is asked of a pair, in this
/// call or an earlier one), as far as the curve goes but no farther than a few times the size of
/// S1.
template <class Context, class Pair, class FirstVisit>
std::vector<TracedRimSegment> trace_rim(const Context& ctx, std::vector<Pair> pending, FirstVisit first_visit) {
  const Surface<2>& s1 = ctx.s1;
  const Surface<2>& s2 = ctx.s2;
  std::vector<TracedRimSegment> traced;
  const std::size_t step_cap = 4 * static_cast<std::size_t>(s1.element_count()) + 1024;
  std::array<RimEnd, 2> ends;
  for (std::size_t steps = 0; !pending.empty() && steps < step_cap;) {
    const auto [t, a, level] = pending.back();
    pending.pop_back();
    if (!first_visit(t, a, level)) continue;
    ++steps;
    if (rim_segment(ctx, ctx.rim_level(level).mu, t, a, ends) != 2) continue;
    traced.push_back({t, a, level, ends});
    for (const RimEnd& end : ends) {
      if (end.on_target_edge) {
        if (const Index next = other_element(s2.edge_elements(end.edge), a); next != invalid_index)
          pending.push_back({t, next, level});
      } else if (const Index next = other_element(s1.edge_elements(end.edge), t); next != invalid_index) {
        pending.push_back({next, a, level});
      }
    }
  }
  return traced;
}

}  // namespace

template <int d>
SurfacePoint<d> ProjectionInsertion<d>::point_on_target_edge(Index e, double eta) const {
  SurfacePoint<d> p;
  if constexpr (d == 2) {
    p.element = ctx_.s2.edge_elements(e).front().element;
    p.local = local_on_edge_of(ctx_.s2, p.element, e, eta);
  }
  return p;
}

template <int d>
Index ProjectionInsertion<d>::rim_node_inside(Index element, Index e, int level, const LocalPoint<d>& local,
                                              double eta) {
  if constexpr (d == 2) {
    const auto [at, fresh] = rim_inside_[level].try_emplace(pair_key(element, e), invalid_index);
    if (!fresh) return at->second;
    if (!(eta > rim_margin && eta < 1.0 - rim_margin)) return invalid_index;
    try {
      at->second = builder_.add_rim_node({element, local}, point_on_target_edge(e, eta));
      ++rim_nodes_made_;
      rim_seeds_.push_back({element, e, level});
    } catch (const BuilderError&) {
      // e.g. the point snaps onto an S1 vertex that holds the preimage of an S2 vertex
    }
    return at->second;
  }
  return invalid_index;
}

template <int d>
Index ProjectionInsertion<d>::rim_node_on_edge(Index edge, double t, Index target, const LocalPoint<d>& image) {
  if constexpr (d == 2) {
    auto& list = rim_on_edge_[edge];
    for (const auto& [parameter, node] : list)
      if (std::abs(parameter - t) <= rim_margin) return node;
    // a crossing of an S2 edge's preimage at the same point: the rim is not made there
    for (Index i = used_first_[edge]; i != invalid_index; i = used_parameters_[i].next)
      if (std::abs(used_parameters_[i].t - t) <= rim_margin) return invalid_index;
    const Index element = ctx_.s1.edge_elements(edge).front().element;
    Index node = invalid_index;
    try {
      node = builder_.add_rim_node({element, local_on_edge_of(ctx_.s1, element, edge, t)}, {target, image});
      ++rim_nodes_made_;
    } catch (const BuilderError&) {
    }
    list.emplace_back(t, node);
    return node;
  }
  return invalid_index;
}

template <int d>
void ProjectionInsertion<d>::insert_rim(ProjectionReport<d>& report) {
  if constexpr (d == 2) {
    // 1. Trace: the pairs the curve passes, in the order met. Where the tracing goes next depends
    //    on the segments alone, not on whether they bound D, so the costly tests of that (step 2)
    //    can wait and run on all threads.
    const std::vector<TracedRimSegment> traced =
        trace_rim(ctx_, rim_tracing_starts(), [this](Index t, Index a, int level) {
          return rim_pairs_done_[level].insert(pair_key(t, a)).second;  // per level, kept for the next call
        });
    // 2. Judge each segment on its own (pure tests of the geometry: the same for any thread count).
    //    Where the rays fold before the plane of the S2 triangle, the segment becomes no rim edge,
    //    and its ends no rim nodes: a node no rim edge and no piece reaches would keep the faces
    //    around it from mapping into one S2 triangle (the tracing went on beyond: the curve may
    //    leave the fold). Likewise where a nearer sheet of S2 hides the segment, tested at its
    //    midpoint (at a bound of the band only: nothing is nearer than mu = 0). A rim segment is
    //    shorter than its element, and a sheet that hides part of it ends on its own rim or
    //    boundary there.
    std::vector<char> bounds_domain(traced.size());
    parallel_for_chunks(traced.size(), rim_judging_chunk, ctx_.threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const TracedRimSegment& seg = traced[i];
        const double mu = ctx_.rim_level(seg.level).mu;
        const LocalPoint<2> middle =
            0.5 * (end_on_element(ctx_, seg.element, seg.ends[0]) + end_on_element(ctx_, seg.element, seg.ends[1]));
        bounds_domain[i] = rays_unfolded_in_front(ctx_, seg.element, seg.target) &&
                           (mu == 0.0 || !hidden_by_nearer_sheet(ctx_, seg.element, middle, mu, seg.target));
      }
    });
    // 3. Insert, in the tracing's order: the rim nodes and edges of the segments that bound D.
    for (std::size_t i = 0; i < traced.size(); ++i) {
      if (!bounds_domain[i]) continue;
      const auto& [t, a, level, ends] = traced[i];
      std::array<Index, 2> nodes{invalid_index, invalid_index};
      for (int k = 0; k < 2; ++k) {
        const RimEnd& end = ends[k];
        if (end.on_target_edge) {
          // the first rim node of an S2 edge that no walk gave a piece: a walk starts there
          const bool unwalked = inserted_[end.edge] == 0 && !rim_inside_[level].contains(pair_key(t, end.edge));
          nodes[k] = rim_node_inside(t, end.edge, level, end.local, end.parameter);
          if (unwalked && nodes[k] != invalid_index)
            unwalked_.push_back({end.edge, RimPoint<d>{t, end.local, end.parameter, level}});
        } else {
          nodes[k] = rim_node_on_edge(end.edge, end.parameter, a, end.local);
        }
      }
      if (nodes[0] == invalid_index || nodes[1] == invalid_index) continue;
      try {
        builder_.add_rim_edge(nodes[0], nodes[1]);
        ++report.rim_edges;
      } catch (const BuilderError&) {
      }
    }
  }
  report.rim_nodes = rim_nodes_made_;
}

template <int d>
std::vector<typename ProjectionInsertion<d>::RimPair> ProjectionInsertion<d>::rim_tracing_starts() {
  std::vector<RimPair> pending;  // taken from the back
  if constexpr (d == 2) {
    // on the first call, last of all: where the rim crosses S1 edges between a vertex whose ray
    // meets S2 inside the band and one whose ray does not, for loops of the rim no piece ends on
    if (rim_seeds_traced_ == 0 && ctx_.ends_on_rim()) seed_rim_at_straddling_edges(pending);
    // from the seeds not traced from yet, the first of them first
    for (std::size_t i = rim_seeds_.size(); i-- > rim_seeds_traced_;)
      for (const auto& inc : ctx_.s2.edge_elements(rim_seeds_[i].target_edge))
        pending.push_back({rim_seeds_[i].element, inc.element, rim_seeds_[i].level});
    rim_seeds_traced_ = rim_seeds_.size();
  }
  return pending;
}

template <int d>
void ProjectionInsertion<d>::seed_rim_at_straddling_edges(std::vector<RimPair>& pending) const {
  if constexpr (d == 2) {
    const Surface<2>& s1 = ctx_.s1;
    const Surface<2>& s2 = ctx_.s2;
    // per S1 vertex: 0 its ray meets S2 inside the band, -1 / +1 only below / beyond it, 2 not at all
    auto outside_mu = [&](Index v) -> double {
      return state_.ray_outside_band.empty() ? std::numeric_limits<double>::quiet_NaN()
                                             : static_cast<double>(state_.ray_outside_band[v]);
    };
    // the distance along the ray to the vertex's hit, inside the band or not; NaN if none
    auto hit_mu = [&](Index v) -> double {
      if (const auto& image = state_.vertex_image[v])
        return (s2.world_position(image->element, image->local) - s1.vertex(v)).dot(ctx_.vertex_directions[v]);
      return outside_mu(v);
    };
    auto side = [&](Index v) -> int {
      if (state_.vertex_image[v]) return 0;
      const double mu = outside_mu(v);
      return std::isnan(mu) ? 2 : (mu < 0.0 ? -1 : 1);
    };
    // Each S1 edge is searched on its own: the edges go in pieces to all threads, and the pieces'
    // pairs are appended in edge order, so the tracing (and the map) is the same for every
    // thread count.
    const auto n = static_cast<std::size_t>(s1.edge_count());
    const std::size_t pieces_per_thread = 4;
    const std::size_t size = std::max<std::size_t>(1024, (n + pieces_per_thread * ctx_.threads - 1) /
                                                              (pieces_per_thread * ctx_.threads));
    std::vector<std::vector<RimPair>> found((n + size - 1) / size);
    parallel_for_pieces_of_size(n, size, ctx_.threads, [&](std::size_t piece, std::size_t begin, std::size_t end) {
      for (auto edge = static_cast<Index>(begin); edge < static_cast<Index>(end); ++edge) {
        const auto ev = s1.edge_vertices(edge);
        if (side(ev[0]) == side(ev[1])) continue;
        const double length = (s1.vertex(ev[1]) - s1.vertex(ev[0])).norm();
        for (int level = 0; level < ctx_.rim_level_count(); ++level) {
          const double mu = ctx_.rim_level(level).mu;
          // A hit outside the band far from this bound lies on another sheet of S2 (the far side
          // of a body, another body): the level set there is no boundary of D, whose points take
          // the nearer hit. Across one S1 edge a sheet's distance moves by about its length.
          if (std::abs(hit_mu(ev[0]) - mu) > length || std::abs(hit_mu(ev[1]) - mu) > length) continue;
          const WorldPoint<2> p0 = s1.vertex(ev[0]) + mu * ctx_.vertex_directions[ev[0]];
          const WorldPoint<2> p1 = s1.vertex(ev[1]) + mu * ctx_.vertex_directions[ev[1]];
          const double reach = 0.5 * (p1 - p0).norm() + 1.01 * ctx_.s2_index->radius;
          for (const Index a : ctx_.s2_index->within(0.5 * (p0 + p1), reach)) {
            const std::optional<Pierce> p = segment_through_triangle(p0, p1, corners_of(s2, a));
            if (!p || !strictly_inside(p->barycentric, rim_margin)) continue;
            for (const auto& inc : s1.edge_elements(edge)) found[piece].push_back({inc.element, a, level});
          }
        }
      }
    });
    for (const std::vector<RimPair>& pairs : found) pending.insert(pending.end(), pairs.begin(), pairs.end());
  }
}

template <int d>
std::vector<RimStart<d>> ProjectionInsertion<d>::take_unwalked_rim_crossings() {
  std::vector<RimStart<d>> out;
  out.swap(unwalked_);
  std::sort(out.begin(), out.end(), [](const RimStart<d>& a, const RimStart<d>& b) {
    return a.target_edge != b.target_edge ? a.target_edge < b.target_edge : a.at.eta < b.at.eta;
  });
  return out;
}

// the members defined here (the rest of the class is instantiated in projection_insertion.cpp)
#define PLMAP_RIM_MEMBERS(d)                                                                               \
  template SurfacePoint<d> ProjectionInsertion<d>::point_on_target_edge(Index, double) const;              \
  template Index ProjectionInsertion<d>::rim_node_inside(Index, Index, int, const LocalPoint<d>&, double); \
  template Index ProjectionInsertion<d>::rim_node_on_edge(Index, double, Index, const LocalPoint<d>&);     \
  template void ProjectionInsertion<d>::insert_rim(ProjectionReport<d>&);                                  \
  template std::vector<typename ProjectionInsertion<d>::RimPair> ProjectionInsertion<d>::rim_tracing_starts(); \
  template std::vector<RimStart<d>> ProjectionInsertion<d>::take_unwalked_rim_crossings();               \
  template void ProjectionInsertion<d>::seed_rim_at_straddling_edges(std::vector<RimPair>&) const;
PLMAP_RIM_MEMBERS(1)
PLMAP_RIM_MEMBERS(2)
#undef PLMAP_RIM_MEMBERS

}  // namespace plmap::projection
