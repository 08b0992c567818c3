// Maps by normal projection (paper section 3.2), the driver: it runs the phases in order and
// times them. Each phase is a unit of its own (projection_context.hpp lists them):
//  0. set-up (projection_context): the direction field, focal-free distances, kd-trees, limits;
//  1. ghost rays (projection_ghost_rays): the ray from every S1 vertex against S2;
//  2. vertex preimages (projection_vertex_preimages): eq. (3) for every S2 vertex, seeded from
//     the nearest S1 elements and then from the ray hits;
//  3. sheet selection (projection_sheet_selection): of coincident preimages, and of regions whose
//     images overlap on S2, the nearer is kept;
//  4. edge walks (projection_edge_walks): the preimage of every S2 edge, walked across S1 from
//     the preimage of its first vertex and from every point where it enters S1 across ∂S1;
//  5. insertion (projection_insertion): everything entered into the MapBuilder in index order,
//     then finalize; after it D leaves out where the rays fold (projection_fold_removal) and the
//     farther of overlapping sheets (3., projection_sheet_selection).
// Phases 1, 2 and 4 compute into per-item slots, in parallel; the builder is fed sequentially in
// index order, so the result does not depend on the number of threads.

#include "projection_context.hpp"
#include "projection_edge_walks.hpp"
#include "projection_fold_rim.hpp"
#include "projection_fold_removal.hpp"
#include "projection_ghost_rays.hpp"
#include "projection_insertion.hpp"
#include "projection_sheet_selection.hpp"
#include "projection_vertex_preimages.hpp"
#include "spatial_renumbering.hpp"
#include "unit_scale.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/ordered_pipeline.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <algorithm>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace plmap {

std::string_view to_string(EdgeFailureReason reason) {
  switch (reason) {
    case EdgeFailureReason::discontinuity: return "discontinuity";
    case EdgeFailureReason::solver_failure: return "solver_failure";
    case EdgeFailureReason::distance_limit: return "distance_limit";
    case EdgeFailureReason::vertex_conflict: return "vertex_conflict";
    case EdgeFailureReason::endpoint_without_preimage: return "endpoint_without_preimage";
    case EdgeFailureReason::walk_limit: return "walk_limit";
    case EdgeFailureReason::builder_rejected: return "builder_rejected";
    case EdgeFailureReason::overlap: return "overlap";
    case EdgeFailureReason::fold: return "fold";
    case EdgeFailureReason::hidden: return "hidden";
  }
  return "unknown";
}


namespace {

using namespace projection;

/// The builder the insertion feeds, with the projection's snapping rule, orientation and threads.
template <int d>
MapBuilder<d> builder_for(const ProjectionContext<d>& ctx) {
  BuilderOptions options;
  options.snap_tolerance = ctx.options.snap_tolerance;
  options.orientation = ctx.options.orientation;
  options.threads = ctx.threads;
  // Where the projection folds, preimages of S2 edges cross on S1; those edges are left out
  // and reported (EdgeFailureReason::overlap) instead of losing the whole map.
  options.drop_conflicting_edges = true;
  // Faces that a partly inserted S2 edge leaves without one S2 element keep the triangles that
  // map into one; their images are compared with the rest by the sheet selection, without which
  // they could overlap it (BuilderOptions::split_unmapped_faces).
  options.split_unmapped_faces = ctx.options.keep_nearer_sheet;
  // room for the cuts of regions across a fold (clip_regions, after finalize): about 1 % more
  // nodes and regions on the femur pair; untouched unless used (BuilderOptions::spare_room)
  if constexpr (d == 2) options.spare_room = 0.02;
  // the images' measures, which the fold and sheet tests need, taken while finalize writes the
  // region maps instead of measured afresh (projection_fold_removal.cpp)
  options.measure_images = true;
  return MapBuilder<d>(ctx.s1_shared, ctx.s2_shared, options);
}

/// Phases 4 and 5 for the S2 edges. The edges are planned in blocks of consecutive indices on all
/// threads, each block into the flat buffers of its slot, and the blocks are fed to the builder on
/// this thread, in index order, while the blocks after them are planned: the walks read nothing
/// the insertion changes, so this is the same as planning all edges first, and only a few blocks'
/// plans are ever held in memory. Seconds: the insertion's own; the rest of the phase counts as
/// walks.
template <int d, class Solver>
void walk_and_insert_edges(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver,
                           ProjectionInsertion<d>& insertion, ProjectionReport<d>& report) {
  const Index n2e = ctx.s2.edge_count();
  const std::size_t slots = ctx.threads == 1 ? 1 : 4 * std::size_t{ctx.threads};
  std::vector<PlanBuffer<d>> buffers(slots);
  std::vector<std::vector<PlannedEdge>> planned(slots);
  const auto t0 = Clock::now();
  double inserting = 0.0;
  produce_in_parallel_consume_in_order(
      static_cast<std::size_t>(n2e), static_cast<std::size_t>(edge_plan_block), slots, ctx.threads,
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        plan_edge_block(ctx, state, solver, static_cast<Index>(begin), static_cast<Index>(end),
                        static_cast<unsigned>(slot), buffers[slot], planned[slot]);
      },
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        const auto t1 = Clock::now();
        insertion.insert_planned_edges(static_cast<Index>(begin), static_cast<Index>(end), planned[slot], buffers,
                                       report);
        inserting += seconds_since(t1);
        if (end % (16 * static_cast<std::size_t>(edge_plan_block)) == 0 || end == static_cast<std::size_t>(n2e))
          report_progress(ctx.options.progress, "S2 edges", static_cast<Index>(end), n2e);  // every 4096 edges
      });
  report.seconds.insertion += inserting;
  report.seconds.edge_walks += seconds_since(t0) - inserting;
}

/// The rank and S2 triangle of every S1 vertex's nearest ray hit (ProjectionState::
/// nearest_hit_rank), for the walks' test of a nearer sheet.
void record_nearest_hits(const ProjectionContext<2>& ctx, const std::vector<std::optional<SurfacePoint<2>>>& hit,
                         ProjectionState<2>& state) {
  const Index n1v = ctx.s1.vertex_count();
  state.nearest_hit_rank.resize(static_cast<std::size_t>(n1v));
  state.nearest_hit_element.resize(static_cast<std::size_t>(n1v));
  state.nearest_hit_vertex.resize(static_cast<std::size_t>(n1v));
  parallel_ranges(static_cast<std::size_t>(n1v), ctx.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const auto& h = hit[v];
      state.nearest_hit_element[v] = h ? h->element : invalid_index;
      state.nearest_hit_vertex[v] = invalid_index;
      if (h) {
        const Barycentric<2> b = barycentric_from_local<2>(h->local);
        for (int k = 0; k < 3; ++k)
          if (b(k) >= 1.0 - 1e-9) state.nearest_hit_vertex[v] = ctx.s2.element(h->element)[k];
      }
      state.nearest_hit_rank[v] =
          h ? ctx.rank((ctx.s2.world_position(h->element, h->local) - ctx.s1.vertex(static_cast<Index>(v)))
                           .dot(ctx.vertex_directions[v]))
            : std::numeric_limits<double>::infinity();
    }
  });
}

template <int d, class Solver>
ProjectionResult<d> run_projection(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                                   const ProjectionOptions& options, const Solver& solver) {
  const auto t_total = Clock::now();
  ProjectionReport<d> report;
  auto t0 = Clock::now();
  ProjectionContext<d> ctx(std::move(s1), std::move(s2), options);
  report.seconds.setup = seconds_since(t0);
  const Index n2v = ctx.s2.vertex_count(), n1v = ctx.s1.vertex_count();

  // ---- 1. ghost rays -------------------------------------------------------------------------
  // The rays come first (they do not depend on the preimages): their hits on S2 seed the
  // second search for S2 vertices that the search from nearby S1 elements does not map.
  t0 = Clock::now();
  report_progress(options.progress, "rays from S1 vertices", 0, n1v);
  std::vector<float> ray_outside_band;  // the rim's seeds (projection_rim.cpp)
  std::vector<std::optional<SurfacePoint<d>>> hit =
      cast_rays_from_s1_vertices(ctx, ctx.ends_on_rim() ? &ray_outside_band : nullptr);
  report.seconds.ghost_nodes = seconds_since(t0);
  report_progress(options.progress, "rays from S1 vertices", n1v, n1v);

  // ---- 2. vertex preimages -------------------------------------------------------------------
  t0 = Clock::now();
  report_progress(options.progress, "S2 vertex preimages", 0, n2v);
  VertexPreimages<d> preimages = find_vertex_preimages(ctx, solver, hit);
  report.vertices_found_by_ray_hits = preimages.found_by_ray_hits;
  report.seconds.vertex_preimages = seconds_since(t0);
  report_progress(options.progress, "S2 vertex preimages", n2v, n2v);

  // ---- 3. and 5. the nodes: vertex preimages (the nearest of coincident ones), ghost nodes ---
  t0 = Clock::now();
  MapBuilder<d> builder = builder_for(ctx);
  ProjectionState<d> state(n1v, n2v, ctx.threads);
  state.ray_outside_band = std::move(ray_outside_band);
  if constexpr (d == 2) record_nearest_hits(ctx, hit, state);
  ProjectionInsertion<d> insertion(ctx, state, builder);
  report.target_vertices = n2v;
  report.domain_vertices = n1v;
  insertion.insert_vertex_preimages(preimages.preimage, report);
  report.seconds.insertion += seconds_since(t0);
  std::vector<std::optional<SurfacePoint<d>>>().swap(preimages.preimage);

  t0 = Clock::now();
  insertion.insert_ghost_nodes(hit, report);
  report.seconds.insertion += seconds_since(t0);
  std::vector<std::optional<SurfacePoint<d>>>().swap(hit);

  // ---- 4. and 5. the edges -------------------------------------------------------------------
  t0 = Clock::now();
  const Index n2e = ctx.s2.edge_count();
  report_progress(options.progress, "S2 edges", 0, n2e);
  state.boundary_entries = find_boundary_entries(ctx, state, solver);
  report.boundary_entries = static_cast<Index>(state.boundary_entries.size());
  report.seconds.edge_walks += seconds_since(t0);
  report.target_edges = n2e;
  walk_and_insert_edges(ctx, state, solver, insertion, report);
  // the rim of D where S2 leaves the band of distances, traced from where pieces ended on it
  t0 = Clock::now();
  insertion.insert_rim(report);
  // S2 edges that dip into the band with both vertices outside it are found by the tracing
  // only: walks start at their rim crossings, and the tracing goes on from where those end
  if (ctx.ends_on_rim()) {
    PlanBuffer<d> buffer;
    std::vector<Index> edges;
    std::vector<PlannedEdge> planned;
    for (int round = 0; round < options.search_limits.rim_walk_rounds; ++round) {
      const std::vector<RimStart<d>> starts = insertion.take_unwalked_rim_crossings();
      if (starts.empty()) break;
      plan_rim_walks(ctx, state, solver, std::span<const RimStart<d>>(starts), buffer, edges, planned);
      insertion.insert_rim_walks(edges, planned, buffer, report);
      insertion.insert_rim(report);
    }
  }
  // where the sheets on both sides of a fold meet: the rim between their meeting points
  if constexpr (d == 2) {
    if (options.fold_rim) {
      const std::vector<FoldRimPath> paths =
          trace_fold_rims(ctx, solver, std::span<const FoldRimNode>(insertion.fold_rim_points()));
      insertion.insert_fold_rims(std::span<const FoldRimPath>(paths), report);
    }
  }
  insertion.declare_edges_without_pieces_outside();
  report.seconds.insertion += seconds_since(t0);
  // what the projection no longer needs, freed before finalize (which has the memory peak);
  // the directions and focal-free distances are kept for the fold test of the finished regions
  std::vector<WorldPoint<d>> directions = std::move(ctx.vertex_directions);
  std::vector<double> focal_free_reach = std::move(ctx.focal_free_reach);
  ctx.release_search_data();
  state.release();
  insertion.release_used_points();

  // ---- finalize, and 3. the nearer of overlapping sheets -------------------------------------
  t0 = Clock::now();
  report_progress(options.progress, "finalize", 0, 1);
  FinalizeReport dropped;
  PlMap<d> map = std::move(builder).finalize(&dropped);
  // where the rays fold, D ends (projection_fold_removal.hpp)
  ImageMeasures images = leave_out_folds(map, options.cut_folded_regions, ctx.threads, directions, focal_free_reach,
                                         dropped, report);
  // the fold tests are done: their blocks (a direction per S1 vertex, a distance per element) are
  // reused by the sheet selection, where the end of the projection has its peak memory
  std::vector<WorldPoint<d>>().swap(directions);
  std::vector<double>().swap(focal_free_reach);
  if (options.keep_nearer_sheet) {
    const double before = images.covered.domain;
    keep_nearer_sheet(map, images, ctx.threads, report, std::span<const Index>(dropped.split_targets));
    report.left_out.occluded = before - images.covered.domain;
  }
  report.seconds.finalize = seconds_since(t0);
  report.reversed_faces = dropped.reversed_faces;
  report.unmapped_faces = dropped.unmapped_faces;
  report.left_out.outside = dropped.left_out.outside;
  report.left_out.reversed = dropped.left_out.reversed;
  report.left_out.unmapped = dropped.left_out.unmapped;
  report.left_out.enclosed = dropped.left_out.enclosed;
  insertion.report_edges_dropped_by_finalize(dropped, report);

  report.solver_calls = ctx.solver_calls.load();
  report.solver_failures = ctx.solver_failures.load();
  ProjectionMeasures measures;
  measures.domain = ctx.s1.measure();
  measures.target = ctx.s2.measure();
  measures.covered_domain = images.covered.domain;
  measures.covered_target = images.covered.target;
  report.seconds.total = seconds_since(t_total);
  report_progress(options.progress, "finalize", 1, 1);
  return ProjectionResult<d>{std::move(map), std::move(report), measures};
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
ProjectionResult<d> project(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                            const ProjectionOptions& options) {
  if (!s1 || !s2) throw Error("project: both surfaces are required");
  using projection::Clock, projection::seconds_since;
  const auto t0 = Clock::now();
  const SolverKind kind = solver_kind_from_string(options.solver);
  // computed on copies in spatial order when the input is in a poor one (spatial_renumbering.hpp);
  // S1 = S2 as one object stays one object: the projection recognises the identity by it
  const projection::RenumberingChoice renumber = projection::renumbering_choice<d>(*s2, s1 == s2, options.renumbering);
  const unsigned threads = resolve_thread_count(options.threads);
  const auto r1 = projection::renumbered_or_kept<d>(s1, renumber.domain, threads);
  const auto r2 = s2 == s1 ? r1 : projection::renumbered_or_kept<d>(s2, renumber.target, threads);
  const ProjectionOptions renumbered_options = projection::options_for_renumbered(options, r1);
  const double copying = seconds_since(t0);
  // and on unit-size copies, so that no product of lengths overflows or underflows
  const auto unit = projection::unit_scaled<d>(r1.surface, r2.surface);
  const ProjectionOptions unit_options = projection::options_for_unit_scale(renumbered_options, unit.exponent);
  auto result = with_solver(kind, options.solver_tolerance, [&](const auto& solver) {
    return run_projection<d>(unit.s1, unit.s2, unit_options, solver);
  });
  result = projection::in_user_units<d>(std::move(result), r1.surface, r2.surface, unit.exponent);
  // the rules go with the map, so that a check against rays applies them unasked
  MapProvenance provenance;
  record_projection_rules(projection_rules(options, d), provenance);
  if (!r1.renumbered() && !r2.renumbered()) {
    result.map.set_provenance(std::move(provenance));
    return result;
  }
  const auto t1 = Clock::now();
  result = projection::in_original_numbering<d>(std::move(result), r1, r2, s1, s2, threads);
  result.report.renumbered_domain = r1.renumbered();
  result.report.renumbered_target = r2.renumbered();
  result.report.seconds.renumbering = copying + seconds_since(t1);
  result.report.seconds.total += result.report.seconds.renumbering;
  result.map.set_provenance(std::move(provenance));
  return result;
}

ProjectionRules projection_rules(const ProjectionOptions& options, int dimension) {
  ProjectionRules rules;
  rules.max_distance = options.max_distance;
  rules.max_distance_is_relative = options.max_distance_is_relative;
  rules.allow_negative_distance = options.allow_negative_distance;
  rules.normal_check = options.normal_check;
  if (!options.directions.empty())
    rules.directions_fingerprint = directions_fingerprint(options.directions, dimension + 1);
  return rules;
}

template ProjectionResult<1> project<1>(std::shared_ptr<const Surface<1>>, std::shared_ptr<const Surface<1>>,
                                        const ProjectionOptions&);
template ProjectionResult<2> project<2>(std::shared_ptr<const Surface<2>>, std::shared_ptr<const Surface<2>>,
                                        const ProjectionOptions&);

}  // namespace plmap
