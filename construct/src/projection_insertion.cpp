// Normal projection, phase 5: insertion (projection_insertion.hpp).

#include "projection_insertion.hpp"

#include "projection_sheet_selection.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/snapping.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <utility>

namespace plmap::projection {

template <int d>
ProjectionInsertion<d>::ProjectionInsertion(const ProjectionContext<d>& ctx, ProjectionState<d>& state,
                                            MapBuilder<d>& builder)
    : ctx_(ctx), state_(state), builder_(builder) {
  // per S1 edge, S1 vertex and S2 edge: on huge pages, first touched on all threads
  // (parallel_first_touch.hpp)
  if constexpr (d == 2)
    assign_on_huge_pages(used_first_, static_cast<std::size_t>(ctx_.s1.edge_count()), invalid_index, ctx_.threads);
  assign_on_huge_pages(crossed_vertex_, static_cast<std::size_t>(ctx_.s1.vertex_count()), invalid_index, ctx_.threads);
  assign_on_huge_pages(inserted_, static_cast<std::size_t>(ctx_.s2.edge_count()), {}, ctx_.threads);
  // One used parameter per crossing inside an S1 edge, grown to millions: room taken once, as
  // the builder does for its nodes (MapBuilder::Impl::reserve_expected_sizes, which explains the
  // estimate; room never written costs address space only).
  if constexpr (d == 2) {
    try {
      reserve_on_huge_pages(used_parameters_, static_cast<std::size_t>(
          8.0 * std::sqrt(static_cast<double>(ctx_.s1.edge_count()) * static_cast<double>(ctx_.s2.edge_count()))));
    } catch (const std::bad_alloc&) {
      // address space refused (strict overcommit, huge inputs): a hint only, the list grows as needed
    }
  }
}

template <int d>
void ProjectionInsertion<d>::insert_vertex_preimages(const std::vector<std::optional<SurfacePoint<d>>>& preimage,
                                                     ProjectionReport<d>& report) {
  const Index n2v = ctx_.s2.vertex_count();
  // state_.target_place first holds every preimage's place; those that are not inserted lose it below
  for (Index q = 0; q < n2v; ++q)
    if (preimage[q]) state_.target_place[q] = ctx_.place_of(*preimage[q]);
  const std::vector<bool> loses = coincident_preimage_losers(ctx_, state_.target_place);
  for (Index q = 0; q < n2v; ++q) {
    if (!preimage[q]) continue;
    const Place<d> place = *state_.target_place[q];
    if (loses[q] || (place.kind == PlaceKind::vertex && state_.vertex_state[place.index] != VertexState::free)) {
      ++report.vertex_conflicts;
      state_.target_place[q].reset();
      continue;
    }
    builder_.add_vertex_preimage(q, {preimage[q]->element, ctx_.place_local(*preimage[q])});
    if constexpr (d == 2)
      if (place.kind == PlaceKind::edge) add_used_parameter(place.index, place.t, -1 - q);
    ++report.vertex_preimages;
    if (place.kind == PlaceKind::vertex) {
      state_.vertex_state[place.index] = VertexState::corner;
      state_.vertex_image[place.index] = SurfacePoint<d>{ctx_.s2.vertex_elements(q).front(),
                                                   local_of_corner(ctx_.s2, ctx_.s2.vertex_elements(q).front(), q)};
    }
  }
}

// S1 vertices that became preimages of S2 vertices are no longer free.
template <int d>
void ProjectionInsertion<d>::insert_ghost_nodes(const std::vector<std::optional<SurfacePoint<d>>>& hit,
                                                ProjectionReport<d>& report) {
  const Index n1v = ctx_.s1.vertex_count();
  for (Index v = 0; v < n1v; ++v) {
    if (!hit[v] || state_.vertex_state[v] != VertexState::free) continue;
    Barycentric<d> b = ctx_.clean_barycentric(hit[v]->local);
    int at_vertex = -1;
    for (int k = 0; k <= d; ++k)
      if (b(k) == 1.0) at_vertex = k;
    const SurfacePoint<d> image{hit[v]->element, local_from_barycentric<d>(b)};
    if (at_vertex >= 0) {
      const Index q = ctx_.s2.element(hit[v]->element)[at_vertex];
      if (state_.target_place[q]) {
        ++report.ghost_conflicts;
        continue;
      }
      builder_.add_ghost_node(v, image);  // becomes the preimage of q (a corner node)
      Place<d> p;
      p.kind = PlaceKind::vertex;
      p.index = v;
      state_.target_place[q] = p;
      state_.vertex_state[v] = VertexState::corner;
      ++report.vertices_mapped_by_ray;
      ++report.vertex_preimages;
    } else {
      builder_.add_ghost_node(v, image);
      state_.vertex_state[v] = VertexState::ghost;
      ++report.ghost_nodes;
    }
    state_.vertex_image[v] = image;
  }
}

template <int d>
void ProjectionInsertion<d>::insert_planned_edges(Index block, Index block_end, const std::vector<PlannedEdge>& planned,
                                                  std::vector<PlanBuffer<d>>& buffers, ProjectionReport<d>& report) {
  for (Index e = block; e < block_end; ++e)
    inserted_[e] = insert_planned_edge(e, planned[e - block], buffers[planned[e - block].worker], report);
}

template <int d>
void ProjectionInsertion<d>::declare_outside(Index e) {
  // With a rim, a walk from a rim crossing the tracing finds may still give the edge a piece
  // (insert_rim_walks): the declaration waits until the rim is done.
  if (ctx_.ends_on_rim())
    edges_declared_outside_.push_back(e);
  else
    builder_.add_edge_outside_domain(e);
}

template <int d>
void ProjectionInsertion<d>::declare_edges_without_pieces_outside() {
  for (const Index e : edges_declared_outside_)
    if (inserted_[e] == 0 && !builder_.has_edge(e)) builder_.add_edge_outside_domain(e);
  std::vector<Index>().swap(edges_declared_outside_);
  std::vector<Index>().swap(edges_counted_outside_);
}

template <int d>
void ProjectionInsertion<d>::insert_rim_walks(std::span<const Index> edges, const std::vector<PlannedEdge>& planned,
                                              PlanBuffer<d>& buffer, ProjectionReport<d>& report) {
  // the edges had no piece (take_unwalked_rim_crossings hands out no other), so what is entered
  // now is all they have
  for (std::size_t i = 0; i < edges.size(); ++i) {
    PlannedEdge plan = planned[i];
    plan.outside = false;  // declared (or not) once the rim is done
    inserted_[edges[i]] = insert_planned_edge(edges[i], plan, buffer, report);
    // an edge whose walks found nothing at all was counted outside D; now it has a piece
    if (inserted_[edges[i]] != 0 &&
        std::binary_search(edges_counted_outside_.begin(), edges_counted_outside_.end(), edges[i]))
      --report.edges_outside;
  }
}

template <int d>
void ProjectionInsertion<d>::release_used_points() {
  auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
  release(used_first_);
  release(used_parameters_);
  release(crossed_vertex_);
  // the rim's bookkeeping: its nodes and edges are in the builder
  for (auto& m : rim_inside_) release(m);
  release(rim_on_edge_);
  release(rim_seeds_);
  for (auto& m : rim_pairs_done_) release(m);
  release(unwalked_);
}

template <int d>
void ProjectionInsertion<d>::report_edges_dropped_by_finalize(const FinalizeReport& dropped,
                                                              ProjectionReport<d>& report) const {
  for (std::size_t i = 0; i < dropped.dropped_edges.size(); ++i) {
    const Index e = dropped.dropped_edges[i];
    const Index pieces = static_cast<Index>(inserted_[e] & ~inserted_whole);
    if (inserted_[e] & inserted_whole) --report.edges_inserted;
    if constexpr (d == 2) {
      // only the stretch on the conflicting element(s) was dropped: the rest stays, in pieces
      if (pieces == 0) ++report.edges_partly_inserted;
    } else {
      if (pieces > 0) --report.edges_partly_inserted;
      report.edge_pieces -= pieces;
    }
    EdgeNotInserted<d> f;
    f.target_edge = e;
    f.reason = EdgeFailureReason::overlap;
    f.domain_element = dropped.dropped_edge_element[i];
    f.domain_point = ctx_.s1.world_position(f.domain_element, LocalPoint<d>::Constant(1.0 / (d + 1)));
    f.detail = d == 2 ? "its preimage crosses another edge's preimage, runs through a node, or meets this S1 "
                        "element twice: the projection is not injective or not continuous there, and the "
                        "stretch on this element is left out"
                      : "its preimage crosses another edge's preimage, runs through a node, or meets this S1 "
                        "element twice: the projection is not injective or not continuous there";
    report.edges_not_inserted.push_back(std::move(f));
  }
}

// ---- points of S1 already taken ------------------------------------------------------------------
template <int d>
auto ProjectionInsertion<d>::find_used_point(std::span<const Crossing<d>> crossings) const -> std::optional<UsedPoint> {
  for (const auto& c : crossings) {
    Index vertex = invalid_index;
    if constexpr (d == 2) {
      const auto ev = ctx_.s1.edge_vertices(c.domain_edge);
      const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, ctx_.options.snap_tolerance);
      if (snap == EdgeSnap::first_vertex) vertex = ev[0];
      else if (snap == EdgeSnap::second_vertex) vertex = ev[1];
      else {
        for (Index i = used_first_[c.domain_edge]; i != invalid_index; i = used_parameters_[i].next)
          if (const Index owner = used_parameters_[i].owner;
              std::abs(used_parameters_[i].t - c.domain_parameter) <= ctx_.options.snap_tolerance) {
            const Place<d> at = ctx_.edge_place(c.domain_edge, c.domain_parameter);
            return UsedPoint{ctx_.s1.edge_elements(c.domain_edge).front().element, ctx_.world_of(at),
                             fmt::format("its preimage meets {} on S1 edge {} at {:.17g}: the projection is not "
                                         "injective there (directions tangential to S2?)",
                                         owner < 0 ? fmt::format("the preimage of S2 vertex {}", -1 - owner)
                                                   : fmt::format("the preimage of S2 edge {}", owner),
                                         c.domain_edge, c.domain_parameter)};
          }
        continue;
      }
    } else {
      vertex = c.domain_vertex;
    }
    if (crossed_vertex_[vertex] != invalid_index)
      return UsedPoint{ctx_.s1.vertex_elements(vertex).front(), ctx_.s1.vertex(vertex),
                       fmt::format("its preimage passes S1 vertex {}, which the preimage of S2 {} {} passes too: "
                                   "the projection is not injective there (directions tangential to S2?)",
                                   vertex, d == 2 ? "edge" : "segment", crossed_vertex_[vertex])};
  }
  return std::nullopt;
}

template <int d>
void ProjectionInsertion<d>::mark_used_points(std::span<const Crossing<d>> crossings, Index e) {
  for (const auto& c : crossings) {
    if constexpr (d == 2) {
      const auto ev = ctx_.s1.edge_vertices(c.domain_edge);
      const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, ctx_.options.snap_tolerance);
      if (snap == EdgeSnap::first_vertex) crossed_vertex_[ev[0]] = e;
      else if (snap == EdgeSnap::second_vertex) crossed_vertex_[ev[1]] = e;
      else add_used_parameter(c.domain_edge, c.domain_parameter, e);
    } else {
      crossed_vertex_[c.domain_vertex] = e;
    }
  }
}

template <int d>
void ProjectionInsertion<d>::add_used_parameter(Index edge, double t, Index owner) {
  const Index entry = static_cast<Index>(used_parameters_.size());
  used_parameters_backing_.before_append(used_parameters_);
  used_parameters_.push_back({t, owner, invalid_index});
  Index* link = &used_first_[edge];
  while (*link != invalid_index) link = &used_parameters_[*link].next;
  *link = entry;
}

/// Enters one piece of S2 edge e (its rim nodes made already, invalid_index where the builder
/// refused one: the piece then starts at its first crossing or ends at its last one there, as
/// before rim nodes). Returns 2 if it is the whole edge, 1 for a piece, 0 if nothing was entered
/// (a refusal is appended to `rejected`).
template <int d>
int ProjectionInsertion<d>::insert_piece(Index e, std::span<const Crossing<d>> crossings, PieceStart starts_at,
                                         PieceEnd ends_at, PieceRimNodes rims,
                                         std::vector<EdgeNotInserted<d>>& rejected) {
  const bool refused = (starts_at == PieceStart::rim_node && rims.start == invalid_index) ||
                       (ends_at == PieceEnd::rim_node && rims.end == invalid_index);
  if (refused) {
    if (starts_at == PieceStart::rim_node && rims.start == invalid_index) starts_at = PieceStart::first_crossing;
    if (ends_at == PieceEnd::rim_node && rims.end == invalid_index) ends_at = PieceEnd::last_crossing;
    if (crossings.size() + (starts_at != PieceStart::first_crossing) + (ends_at != PieceEnd::last_crossing) < 2)
      return 0;
  }
  try {
    int added = 1;
    if (starts_at == PieceStart::first_vertex && ends_at == PieceEnd::second_vertex) {
      builder_.add_edge(e, crossings);
      added = 2;
    } else {
      if constexpr (d == 2)
        builder_.add_edge_piece(e, crossings, starts_at, ends_at, rims);
      else
        builder_.add_edge_piece(e, crossings, starts_at, ends_at);
    }
    mark_used_points(crossings, e);
    return added;
  } catch (const BuilderError& error) {
    EdgeNotInserted<d> f;
    f.target_edge = e;
    f.reason = EdgeFailureReason::builder_rejected;
    f.detail = error.what();
    rejected.push_back(std::move(f));
  }
  return 0;
}

/// Feeds the planned pieces of S2 edge e to the builder and reports what was left out. Returns
/// inserted_whole if the edge was inserted whole, or'ed with the number of pieces inserted.
template <int d>
std::uint32_t ProjectionInsertion<d>::insert_planned_edge(Index e, const PlannedEdge& plan, PlanBuffer<d>& buffer,
                                                          ProjectionReport<d>& report) {
  if (plan.outside) {
    ++report.edges_outside;
    declare_outside(e);
    if (ctx_.ends_on_rim()) edges_counted_outside_.push_back(e);  // in index order: sorted
  }
  bool whole = false;
  std::uint32_t pieces = 0;
  std::vector<EdgeNotInserted<d>> rejected;
  for (std::uint32_t p = plan.pieces_begin; p < plan.pieces_end; ++p) {
    const auto& piece = buffer.pieces[p];
    const std::span<const Crossing<d>> crossings(buffer.crossings.data() + piece.begin, piece.end - piece.begin);
    if (const auto clash = find_used_point(crossings)) {
      EdgeNotInserted<d> f;
      f.target_edge = e;
      f.reason = EdgeFailureReason::builder_rejected;
      f.domain_element = clash->element;
      f.domain_point = clash->point;
      f.detail = clash->detail;
      rejected.push_back(std::move(f));
      continue;
    }
    auto rim_node_of = [&](std::uint32_t rim) {
      if (rim == PlanBuffer<d>::no_rim) return invalid_index;
      const RimPoint<d>& point = buffer.rim_points[rim];
      if (point.level == fold_rim_level) return fold_rim_node(point, e);
      return rim_node_inside(point.element, e, point.level, point.local, point.eta);
    };
    PieceRimNodes rims;
    if (piece.starts_at == PieceStart::rim_node) rims.start = rim_node_of(piece.start_rim);
    if (piece.ends_at == PieceEnd::rim_node) rims.end = rim_node_of(piece.end_rim);
    const int added = insert_piece(e, crossings, piece.starts_at, piece.ends_at, rims, rejected);
    whole |= added == 2;
    if (added == 1) ++pieces;
    if constexpr (d == 2) {
      if (added == 0) continue;
      // the piece stands: its nodes where it meets the sheet beyond a fold are where the fold rim
      // runs (insert_fold_rims)
      auto note_fold_point = [&](Index node, std::uint32_t rim, bool toward_first) {
        if (node == invalid_index || rim == PlanBuffer<d>::no_rim) return;
        const RimPoint<d>& point = buffer.rim_points[rim];
        if (point.level == fold_rim_level)
          fold_points_.push_back({e, node, point.element, point.local, point.eta, toward_first});
      };
      if (piece.starts_at == PieceStart::rim_node) note_fold_point(rims.start, piece.start_rim, false);
      if (piece.ends_at == PieceEnd::rim_node) note_fold_point(rims.end, piece.end_rim, true);
    }
  }
  // An edge of which no stretch could be inserted (its walks fail at once from both ends)
  // still closes its S2 triangles' regions, as one beyond S1's boundary does: the faces it
  // would split have nodes on both of its sides, so no single S2 element holds their images
  // and they stay outside D, while the triangles' other faces keep their regions.
  if (!whole && pieces == 0 && !plan.outside && !builder_.has_edge(e)) declare_outside(e);
  if (whole) ++report.edges_inserted;
  if (pieces > 0) ++report.edges_partly_inserted;
  report.edge_pieces += static_cast<Index>(pieces);
  for (std::uint32_t f = plan.failures_begin; f < plan.failures_end; ++f)
    report.edges_not_inserted.push_back(std::move(buffer.failures[f]));
  for (auto& f : rejected) report.edges_not_inserted.push_back(std::move(f));
  return (whole ? inserted_whole : 0u) | pieces;
}

template class ProjectionInsertion<1>;
template class ProjectionInsertion<2>;

}  // namespace plmap::projection
