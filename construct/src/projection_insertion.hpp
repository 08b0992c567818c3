#pragma once
// Normal projection, phase 5: insertion. What the searches found is entered into the MapBuilder
// sequentially, in index order, so that the map does not depend on the number of threads: the
// vertex preimages (but of coincident ones only the nearest, sheet selection), the ghost nodes of
// the S1 vertices left free, and the planned pieces of the S2 edges (edge walks). Points of S1
// that an earlier edge already passes are not given to a later one, which is reported instead.

#include "projection_context.hpp"
#include "projection_edge_walks.hpp"
#include "projection_fold_rim.hpp"

#include <plmap/construct/projection_result.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/map_builder.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace plmap::projection {

/// Points of the rim closer than this (in barycentric coordinates or edge parameters) to the
/// side of a triangle or the end of an edge are not made: they would coincide, after the
/// builder's snapping, with a point of the neighbouring triangle's or edge's rim, or a node.
inline constexpr double rim_margin = 1e-9;

template <int d>
class ProjectionInsertion {
 public:
  /// Sets up `state` for the insertion (every S1 vertex free, no S2 vertex placed).
  ProjectionInsertion(const ProjectionContext<d>& ctx, ProjectionState<d>& state, MapBuilder<d>& builder);

  /// The preimages of the S2 vertices (per S2 vertex); fills state.target_place, and marks the
  /// S1 vertices that became corner nodes.
  void insert_vertex_preimages(const std::vector<std::optional<SurfacePoint<d>>>& preimage,
                               ProjectionReport<d>& report);

  /// The ghost nodes: the S1 vertices still free whose ray hits S2 (per S1 vertex). A hit on an
  /// S2 vertex without a preimage makes the S1 vertex that vertex's preimage.
  void insert_ghost_nodes(const std::vector<std::optional<SurfacePoint<d>>>& ray_hits, ProjectionReport<d>& report);

  /// The planned pieces of S2 edges [block, block_end) (plan_edge_block), in index order.
  void insert_planned_edges(Index block, Index block_end, const std::vector<PlannedEdge>& planned,
                            std::vector<PlanBuffer<d>>& buffers, ProjectionReport<d>& report);

  /// d = 2, end_on_rim: the rim of D where S2 leaves the admissible band of distances (passes
  /// behind S1, or beyond the distance limit), traced across S1 from the rim nodes where pieces
  /// ended (projection_rim.cpp): per pair of an S1 element and an S2 triangle whose level sets
  /// of a bound meet along it, a rim edge between the two ends of their intersection. The
  /// tracing runs on this thread, the tests whether each segment bounds D (folds, a nearer
  /// sheet) on all threads, and the nodes and edges are entered in the tracing's order: the rim
  /// is the same for every thread count. Runs after every edge is inserted, before
  /// release_used_points.
  void insert_rim(ProjectionReport<d>& report);

  /// d = 2, end_on_rim: the points where the rim traced so far crosses S2 edges that no walk
  /// gave a piece (both vertices outside the band, the edge dipping into it between them), by
  /// edge and edge parameter; taken, so that each is handed out once. Walks start there
  /// (plan_rim_walks), and insert_rim_walks enters what they find.
  std::vector<RimStart<d>> take_unwalked_rim_crossings();

  /// Enters the pieces planned from unwalked rim crossings (planned[i] for S2 edge edges[i],
  /// all in `buffer`), as insert_planned_edges does; then insert_rim traces on from their rim
  /// nodes.
  void insert_rim_walks(std::span<const Index> edges, const std::vector<PlannedEdge>& planned,
                        PlanBuffer<d>& buffer, ProjectionReport<d>& report);

  /// d = 2, fold_rim: the nodes where inserted pieces end or start at a point where the sheets
  /// on both sides of a fold meet (projection_fold_rim.hpp), in insertion order.
  const std::vector<FoldRimNode>& fold_rim_points() const { return fold_points_; }
  /// Enters the traced preimages of the fold rim between those nodes (trace_fold_rims) as rim
  /// nodes on the S1 edges they cross and rim edges between them; a path of which a node or an
  /// edge is refused ends there.
  void insert_fold_rims(std::span<const FoldRimPath> paths, ProjectionReport<d>& report);

  /// Declares the S2 edges that no walk gave a piece outside D (MapBuilder::
  /// add_edge_outside_domain); with a rim this waits until the rim walks are done.
  void declare_edges_without_pieces_outside();

  /// Frees what only the insertion needs, before finalize; what it inserted per edge stays.
  void release_used_points();

  /// Moves the edges that finalize dropped (their preimages cross) from the inserted ones to
  /// edges_not_inserted (reason overlap).
  void report_edges_dropped_by_finalize(const FinalizeReport& dropped, ProjectionReport<d>& report) const;

 private:
  // ---- insertion: points of S1 already taken ------------------------------------------------------
  /// Two S2 edges whose preimages cross an S1 edge (or pass an S1 vertex) at the same point would
  /// give the builder two nodes at one point (it throws in finalize), and the map could not be
  /// injective there: S2 edges meet only at S2 vertices. This happens where the directions are
  /// tangential to S2 (S2 perpendicular to S1, a vertical wall): edges of S2 then project onto
  /// the same curve. The first edge (in index order, so independent of threads) keeps the point;
  /// a later piece through it is reported, not inserted.
  struct UsedPoint {
    Index element;
    WorldPoint<d> point;
    std::string detail;
  };

  std::optional<UsedPoint> find_used_point(std::span<const Crossing<d>> crossings) const;
  void mark_used_points(std::span<const Crossing<d>> crossings, Index e);
  /// Appends to S1 edge `edge`'s list of used parameters (see used_first_).
  void add_used_parameter(Index edge, double t, Index owner);
  std::uint32_t insert_planned_edge(Index e, const PlannedEdge& plan, PlanBuffer<d>& buffer,
                                    ProjectionReport<d>& report);
  /// MapBuilder::add_edge_outside_domain, at once or, with a rim, once the rim is done.
  void declare_outside(Index e);
  /// Edges whose declaration waits (declare_outside), and of them those counted in
  /// ProjectionReport::edges_outside (no walk found anything, nothing failed), sorted.
  std::vector<Index> edges_declared_outside_, edges_counted_outside_;

  // ---- the rim of D (end_on_rim) ------------------------------------------------------------------
  /// The rim node where S2 edge e pierces the level set `level` (ProjectionContext::rim_level)
  /// of S1 element `element`'s rays at `local` (edge parameter eta), made once per (element,
  /// edge, level); invalid_index if the builder refuses it.
  Index rim_node_inside(Index element, Index e, int level, const LocalPoint<d>& local, double eta);
  /// The rim node where S1 edge `edge` pierces S2 element `target` (parameter t along the S1
  /// edge, image `image` on the target), made once per point; invalid_index if refused or if
  /// another node holds that point of the edge.
  Index rim_node_on_edge(Index edge, double t, Index target, const LocalPoint<d>& image);
  /// The point at parameter eta (from the smaller-index vertex) of S2 edge e, on an S2 element.
  SurfacePoint<d> point_on_target_edge(Index e, double eta) const;
  static std::uint64_t pair_key(Index a, Index b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  }
  /// Per level and (S1 element, S2 edge): the rim node where the edge pierces the element's
  /// level set.
  std::array<std::unordered_map<std::uint64_t, Index>, 2> rim_inside_;
  /// Per S1 edge: the rim nodes on it, (parameter, node).
  std::unordered_map<Index, std::vector<std::pair<double, Index>>> rim_on_edge_;
  /// The (S1 element, S2 edge, level) of the pieces' rim nodes, in insertion order: where the
  /// tracing starts.
  struct RimSeed {
    Index element, target_edge;
    int level;
  };
  std::vector<RimSeed> rim_seeds_;
  /// A pair the rim tracing looks at: S1 element, S2 triangle, level.
  struct RimPair {
    Index element, target;
    int level;
  };
  /// Pairs where the rim crosses an S1 edge whose two vertices' rays meet S2 on different sides
  /// of a bound of the band, or one does and the other misses S2 (ProjectionState::
  /// ray_outside_band; the S2 triangles pierced found through the S2 kd-tree): a stretch of the
  /// rim that no piece ends on (a band crossed by S2 edges whose vertices all lie outside it, or
  /// an island beyond it whose S2 edges all dip in from outside) is traced from there.
  void seed_rim_at_straddling_edges(std::vector<RimPair>& pending) const;
  /// Where insert_rim's tracing starts: on the first call the straddling edges' pairs, then the
  /// pairs of the rim seeds not traced from yet.
  std::vector<RimPair> rim_tracing_starts();
  /// Seeds traced from already (insert_rim runs again after the rim walks, from the new ones),
  /// and the (S1 element, S2 triangle) pairs per level traced so far.
  std::size_t rim_seeds_traced_ = 0;
  std::array<std::unordered_set<std::uint64_t>, 2> rim_pairs_done_;
  /// Rim crossings of S2 edges without a piece, found by the tracing (take_unwalked_rim_crossings).
  std::vector<RimStart<d>> unwalked_;
  Index rim_nodes_made_ = 0;
  /// The node where a piece meets the sheet beyond a fold (RimPoint::level fold_rim_level), made
  /// for each piece; invalid_index if the builder refuses it.
  Index fold_rim_node(const RimPoint<d>& point, Index e);
  /// A rim edge of the fold rim; false if the builder refuses it.
  bool add_fold_rim_edge(Index a, Index b, ProjectionReport<d>& report);
  /// The fold_rim nodes of the pieces inserted so far (fold_rim_points).
  std::vector<FoldRimNode> fold_points_;
  /// Enters one piece of S2 edge e (projection_insertion.cpp says what it returns).
  int insert_piece(Index e, std::span<const Crossing<d>> crossings, PieceStart starts_at, PieceEnd ends_at,
                   PieceRimNodes rims, std::vector<EdgeNotInserted<d>>& rejected);

  /// In the per-edge count of what was inserted: the edge was inserted whole.
  static constexpr std::uint32_t inserted_whole = 1u << 31;

  const ProjectionContext<d>& ctx_;
  ProjectionState<d>& state_;
  MapBuilder<d>& builder_;
  /// Per S1 edge (d = 2): the parameters already holding a node, with their owner (an S2 edge,
  /// or -1 - q for the preimage of S2 vertex q), as lists in insertion order linked through one
  /// array (used_first_[edge] is the first entry). Per S1 vertex: the S2 edge whose preimage passes it.
  struct UsedParameter {
    double t;
    Index owner, next;
  };
  std::vector<Index> used_first_;
  std::vector<UsedParameter> used_parameters_;
  PagesBackedAhead used_parameters_backing_;  // its room backed ahead of the appends
  std::vector<Index> crossed_vertex_;
  /// Per S2 edge: bit 31 (inserted_whole) set if inserted whole, the lower bits count the pieces
  /// inserted.
  std::vector<std::uint32_t> inserted_;
};

}  // namespace plmap::projection
