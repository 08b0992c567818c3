// EditableMap::plan_vertex_removal: one step of paper 3.3.1 on the editing form.
//
// The star of v is given as sheets (one closed fan, or for a vertex on a feature line one open
// fan per side of the line), each flattened by the caller (one planar position per ring vertex,
// v at the origin); each star triangle maps affinely onto its fan triangle, so every node of the
// star's graphs keeps its barycentric coordinates and gets a planar position: the graphs of a
// sheet are merged into one plane graph on its polygon. Vertex preimages are located in the new
// triangles (on a feature line: v and the nodes of the removed line edges move onto the new
// edge joining the line neighbours, at the same parameter in every sheet); every S2 edge
// polyline that runs through the star is cut along the new triangles' interior edges (its old
// crossings on the removed spokes disappear, so inside each new triangle it becomes the
// straight segment between its new crossings). Finally each new triangle's segments are checked
// not to cross, with exact predicates on the shared planar coordinates (only pairs whose bounding
// boxes overlap, found by a sweep along x).
//
// This file holds the entry points and the order of the phases; each phase lives in a file of
// its own (removal_planning.hpp lists them) and shares the call's state through
// EditableMap::RemovalPlanning.

#include "removal_planning.hpp"

#include <algorithm>

namespace plmap {

namespace {

using removal::Vec2;

/// True if the plan's star, flattening and triangulation are those given: one closed sheet, the
/// same ring, the flattening `bound_flat` (kept by the planning call that made the plan) and a
/// triangulation that makes the plan's new triangles.
bool same_closed_star(const VertexRemovalPlan& plan, std::span<const StarSheet> sheets,
                      std::span<const std::vector<Vec2>> flattened,
                      std::span<const std::vector<std::array<int, 3>>> triangulations, const std::vector<Vec2>& bound_flat) {
  if (sheets.size() != 1 || flattened.size() != 1 || triangulations.size() != 1 || !sheets[0].closed) return false;
  const std::vector<Index>& ring = sheets[0].ring;
  if (ring != plan.ring || flattened[0] != bound_flat || triangulations[0].size() != plan.new_triangles.size()) return false;
  for (std::size_t n = 0; n < plan.new_triangles.size(); ++n)
    for (int m = 0; m < 3; ++m) {
      const int i = triangulations[0][n][m];
      if (i < 0 || i >= static_cast<int>(ring.size()) || ring[static_cast<std::size_t>(i)] != plan.new_triangles[n][m]) return false;
    }
  return true;
}

/// The sheets' layout before any geometry: one closed sheet, or open sheets that all run from
/// one line neighbour of v to the other (line_key, smaller first) with a ring vertex between.
RemovalRefusal check_sheet_layout(std::span<const StarSheet> sheets, std::size_t flattened_count,
                                  std::size_t triangulation_count, std::array<Index, 2>& line_key) {
  const int sheet_count = static_cast<int>(sheets.size());
  if (sheet_count == 0 || flattened_count != sheets.size() || triangulation_count != sheets.size())
    return RemovalRefusal::not_a_disk_star;
  const bool on_line = !sheets[0].closed;
  for (const StarSheet& sheet : sheets)
    if (sheet.closed == on_line || (!on_line && sheet_count != 1)) return RemovalRefusal::not_a_disk_star;
  if (!on_line) return RemovalRefusal::none;
  if (sheets[0].ring.size() < 2) return RemovalRefusal::not_a_disk_star;
  line_key = sorted_pair(sheets[0].ring.front(), sheets[0].ring.back());
  for (const StarSheet& sheet : sheets) {
    if (sheet.ring.size() < 2 || sorted_pair(sheet.ring.front(), sheet.ring.back()) != line_key)
      return RemovalRefusal::not_a_disk_star;
    if (sheet.ring.size() == 2) return RemovalRefusal::single_triangle_side;
  }
  return RemovalRefusal::none;
}

}  // namespace

void VertexRemovalPlan::reset() {
  vertex = invalid_index;
  refusal = RemovalRefusal::none;
  ring.clear();
  old_triangles.clear();
  new_triangles.clear();
  old_triangle_sheet.clear();
  new_triangle_sheet.clear();
  line_edge = {invalid_index, invalid_index};
  node_domain_positions.clear();
  node_target_positions.clear();
  max_node_distance = 0.0;
  relocations.clear();
  for (PolylineEdit& e : polyline_edits) {
    e.points.clear();
    spare_edits.push_back(std::move(e));
  }
  polyline_edits.clear();
  triangle_count_at_planning = 0;
  extent = PlanExtent::full;
  blocking_diagonal = {-1, -1};
  blocking_sheet = -1;
  bound_generation = 0;
}

VertexRemovalPlan EditableMap::plan_vertex_removal(Index v, std::span<const Vec2> flattened_ring,
                                                   std::span<const std::array<int, 3>> triangulation,
                                                   PlanExtent extent) const {
  const StarSheet sheet{closed_ring(v), true};
  const std::vector<Vec2> flat(flattened_ring.begin(), flattened_ring.end());
  const std::vector<std::array<int, 3>> triangles(triangulation.begin(), triangulation.end());
  return plan_vertex_removal(v, std::span(&sheet, 1), std::span(&flat, 1), std::span(&triangles, 1), extent);
}

VertexRemovalPlan EditableMap::plan_vertex_removal(Index v, std::span<const StarSheet> sheets,
                                                   std::span<const std::vector<Vec2>> flattened,
                                                   std::span<const std::vector<std::array<int, 3>>> triangulations,
                                                   PlanExtent extent, VertexRemovalPlan storage) const {
  const Impl& s = *impl_;
  thread_local removal::PlanScratch scratch;
  // A full plan of a closed star whose `storage` is the accepted ranking bound that the previous
  // planning call on this thread made on this map, with the same star, flattening and
  // triangulation, continues from it: the star's triangles, the new triangles and the relocated
  // preimages are already in the plan and in `scratch` (the simplifier plans a vertex's bound
  // and then, if it removes it, its full plan: the bound's part cost about a third of the full
  // plan's). Otherwise it starts from scratch, in the buffers of `storage`.
  const bool continuing = extent == PlanExtent::full && storage.extent == PlanExtent::ranking_bound &&
                          storage.accepted() && storage.vertex == v && storage.bound_generation != 0 &&
                          storage.bound_generation == scratch.generation && scratch.owner == impl_.get() &&
                          storage.triangle_count_at_planning == static_cast<Index>(s.triangles.size()) &&
                          same_closed_star(storage, sheets, flattened, triangulations, scratch.bound_flat);
  ++scratch.generation;
  scratch.owner = impl_.get();
  VertexRemovalPlan plan = std::move(storage);
  if (!continuing) plan.reset();
  plan.bound_generation = 0;
  plan.vertex = v;
  plan.extent = extent;
  plan.triangle_count_at_planning = static_cast<Index>(s.triangles.size());
  RemovalRefusal why = RemovalRefusal::none;
  auto refused = [&why](RemovalRefusal phase_result) {
    why = phase_result;
    return why != RemovalRefusal::none;
  };
  auto refuse = [&plan, &why] {
    plan.refusal = why;
    return std::move(plan);
  };

  std::array<Index, 2> line_key{invalid_index, invalid_index};
  if (refused(check_sheet_layout(sheets, flattened.size(), triangulations.size(), line_key))) return refuse();
  const bool on_line = !sheets[0].closed;
  if (on_line) plan.line_edge = line_key;
  const int sheet_count = static_cast<int>(sheets.size());
  if (static_cast<int>(scratch.sheets.size()) < sheet_count) scratch.sheets.resize(static_cast<std::size_t>(sheet_count));
  RemovalPlanning planning{s,           *s.target, plan,     scratch, scratch.sheets, v,
                           sheet_count, on_line,   line_key, s.options.edge_clearance};

  if (continuing) {  // the same contents as the bound's, in the caller's objects of this call
    removal::SheetPlan& sheet = scratch.sheets[0];
    sheet.ring = &sheets[0].ring;
    sheet.flat = flattened[0];
    sheet.triangulation = triangulations[0];
  } else if (refused(planning.collect_star_triangles(sheets, flattened, triangulations))) {
    return refuse();
  }
  const removal::SlotReset slot_reset{scratch};
  planning.mark_star_triangles();
  if (refused(planning.check_line_parameters())) return refuse();
  if (!continuing && (refused(planning.make_new_triangles()) || refused(planning.relocate_preimages())))
    return refuse();
  if (refused(planning.move_line_nodes())) return refuse();

  // A ranking bound ends here: the cut below only adds nodes (crossings) and refusals.
  if (extent == PlanExtent::ranking_bound) {
    plan.bound_generation = scratch.generation;  // a full plan may continue from it (above)
    scratch.bound_flat.assign(scratch.sheets[0].flat.begin(), scratch.sheets[0].flat.end());
    return plan;
  }

  planning.index_moved_preimages();
  // With the deferred cut, the S2 edges are traced once, on the final S1 (to_map): the
  // polylines are neither cut nor checked now, only the straight segments' orientation is.
  if (s.options.defer_cut) return refused(planning.check_straight_folds()) ? refuse() : std::move(plan);
  if (refused(planning.cut_polylines()) || refused(planning.check_pieces())) return refuse();
  return plan;
}

}  // namespace plmap
