#pragma once
/// \file
/// EditableMap: the editing form of a parametrization Ξ: S1 → S2 (d = 2), the unit that
/// simplification changes step by step (paper section 3.3.1). Building (MapBuilder), editing
/// (this class) and querying (PlMap) are separate units; to_map() hands the edited state to the
/// builder, which closes every element and produces the compact PlMap.
///
/// What is stored. S1 starts as S2 itself (Ξ = identity) and loses vertices; its vertices keep
/// their S2 numbers, and every remaining S1 vertex is the preimage of the S2 vertex with the
/// same number. Every other S2 vertex has its preimage strictly inside one S1 triangle
/// (barycentric coordinates). Every S2 edge has its preimage as a polyline on S1: from the
/// preimage of its smaller-index vertex to the larger, through crossings of S1 edges, with the
/// S1 triangle each segment lies in and the position of each point on the S2 edge. Segments
/// are straight in their triangle, so these polylines are exactly the graphs of the paper's
/// data structure, with crossings as intersection nodes.
///
/// One editing step removes an S1 vertex (plan_vertex_removal / apply): the caller gives the
/// flattening of its star (a star-shaped polygon, one position per ring vertex) and the new
/// triangulation of that polygon; the plan merges the star's graphs in the plane, moves every
/// vertex preimage of the star into the new triangles, cuts every S2 edge polyline along the new
/// triangles (new crossings; the old crossings on the removed edges disappear, so the polyline
/// is straightened inside each new triangle) and checks that the result is still a valid map.
/// A step that would make Ξ invalid is refused with a reason, and nothing changes.
///
/// Vertex preimages lie on an S1 edge (touching nodes) only on feature lines, where a removal
/// along the line moves them there; elsewhere a step that would put one within
/// `EditOptions::edge_clearance` of a new edge is refused (see docs/algorithms/simplification.md).

#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/core/surface.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace plmap {

/// Why a vertex removal was refused (one reason per refused plan).
enum class RemovalRefusal {
  none,
  not_a_disk_star,        ///< the star is not one closed fan of consistently oriented triangles
  flattening_not_simple,  ///< the flattened star is not a simple star-shaped polygon
  no_triangulation,       ///< the re-triangulation strategy found no admissible triangulation
  existing_edge,          ///< a new edge or triangle already exists elsewhere in S1
  degenerate_triangle,    ///< a new triangle has (almost) no area in space
  fold_over,              ///< a new triangle faces away from the star it replaces
  node_on_new_edge,       ///< a vertex preimage would lie on (or too close to) a new edge
  edge_along_new_edge,    ///< an S2 edge's preimage would run along, or touch, a new edge
  crossing_edges,         ///< straightened S2 edge preimages would cross, touch or come within the clearance inside a new triangle
  single_triangle_side,   ///< a side of the feature line is one triangle: it would collapse onto the new edge
  edge_reenters_triangle, ///< an S2 edge's preimage would pass through one new triangle twice
  straight_fold,          ///< deferred cut: an S2 triangle's straightened preimage in the star would turn over
};

const char* to_string(RemovalRefusal reason);

/// Tolerances of the editing steps, relative to the element (barycentric / edge parameters) or
/// to the star's size.
struct EditOptions {
  /// A vertex preimage or a crossing closer than this (barycentric, or edge parameter) to a new
  /// S1 edge or vertex makes the step refused: far above the builder's snap tolerance, so the
  /// builder never snaps what the editing kept apart. Times the flattened star's size, also the
  /// distance a node keeps from another S2 edge's straightened preimage (crossing_edges).
  double edge_clearance = 1e-9;
  /// A new triangle whose area is below this times the squared bounding-box diagonal of S2 is
  /// degenerate. Above Surface's own degeneracy threshold (1e-14 times the squared longest
  /// edge), so the final S1 is always a valid Surface.
  double min_relative_area = 1e-12;
  /// The deferred cut: full plans stop after the new triangles and the relocated vertex
  /// preimages (as a ranking bound does) and no S2 edge polyline is cut or checked while
  /// editing; to_map() then traces every S2 edge once, as the straight segment between its ends'
  /// preimages through the final S1 (unfolding the triangles it crosses), and checks that the
  /// traced graph is an embedding with S2's rotation order (see
  /// docs/algorithms/simplification.md, "The deferred cut"). Where a trace cannot be made or the
  /// check fails, to_map() throws DeferredCutFailure and the caller redoes the run with the
  /// per-step cut.
  bool defer_cut = false;
};

/// to_map() of an EditableMap with the deferred cut found no valid straight trace of S2's
/// edges through the final S1; the message says which edge or vertex and why.
class DeferredCutFailure : public Error {
 public:
  using Error::Error;
};

/// One side of the star of an S1 vertex v. A vertex off the feature lines has one closed sheet:
/// its ring, counter-clockwise around v. A vertex on a feature line (exactly two feature edges,
/// to its line neighbours a and b) has one open sheet per side of the line (one on a boundary,
/// two on a sharp edge, more on a non-manifold line): the fan of triangles between the two
/// line spokes, its ring running counter-clockwise around v from one line neighbour to the other.
struct StarSheet {
  std::vector<Index> ring;
  bool closed = true;
};

/// One point of the preimage of an S2 edge on S1 (a polyline, see EditableMap), with the segment
/// that leaves it towards the next point. All of a point's fields sit together, so a polyline is
/// one array: a plan copies a polyline point by point into its edit and apply() copies the edit
/// back, both once per S2 edge in the star of every removal (with one array per field, that was
/// five allocations per S2 edge and five copies per point).
struct PolylinePoint {
  Index vertex = invalid_index;                             ///< the S2 vertex, or invalid for a crossing
  std::array<Index, 2> edge{invalid_index, invalid_index};  ///< a crossing's S1 edge (smaller vertex first)
  /// The S1 triangle of the segment from this point to the next (in a plan's edit, -(k + 1) for
  /// new triangle k); invalid on the last point.
  Index segment_triangle = invalid_index;
  double edge_parameter = 0.0;    ///< a crossing's place on its S1 edge, from the smaller vertex
  double target_parameter = 0.0;  ///< the point's place on the S2 edge, 0 at its smaller vertex
  bool operator==(const PolylinePoint&) const = default;
};

/// How far EditableMap::plan_vertex_removal goes. `ranking_bound` stops after the new triangles
/// and the relocated vertex preimages: no S2 edge polyline is cut and no crossing is checked.
/// It costs a fraction of the full plan, refuses a subset of what the full plan refuses (the
/// same triangulation choices), and its max_node_distance is a lower bound of the full plan's
/// (the nodes of the new crossings are missing), so a simplifier can rank candidates by it and
/// plan fully only the vertex it is about to remove. Such a plan cannot be applied.
enum class PlanExtent { full, ranking_bound };

/// One planned removal of an S1 vertex: the new triangles and where every node of the star goes.
/// Produced by EditableMap::plan_vertex_removal and consumed by EditableMap::apply (or thrown
/// away: planning changes nothing).
struct VertexRemovalPlan {
  Index vertex = invalid_index;
  RemovalRefusal refusal = RemovalRefusal::none;
  /// The ring of the star (counter-clockwise for a closed star; the rings of all sheets, each
  /// vertex once, for a vertex on a feature line) and the star's triangles (S1 triangle ids).
  std::vector<Index> ring;
  std::vector<Index> old_triangles;
  /// New triangles as S1 vertex triples, oriented like the star.
  std::vector<std::array<Index, 3>> new_triangles;
  /// The sheet (StarSheet index) of each old and each new triangle: oracles compare a new
  /// triangle only with the old ones of its own side of a feature line.
  std::vector<int> old_triangle_sheet;
  std::vector<int> new_triangle_sheet;
  /// For a vertex on a feature line: the new S1 edge joining its line neighbours (smaller
  /// first), onto which the nodes of the removed line edges move; invalid otherwise.
  std::array<Index, 2> line_edge{invalid_index, invalid_index};

  /// Geometry the error oracles look at: for every node whose preimage moved or was created
  /// (relocated vertex preimages, new crossings), its position on the new S1 triangles and its
  /// image on S2, both in space.
  std::vector<Eigen::Vector3d> node_domain_positions;
  std::vector<Eigen::Vector3d> node_target_positions;
  /// Largest distance between a node's position and its image (the modified Hausdorff distance
  /// of the step, paper 3.3.1).
  double max_node_distance = 0.0;

  // ---- what apply() writes (internal to EditableMap) ----
  struct Relocation {
    Index target_vertex;
    int new_triangle;  ///< index into new_triangles, or -1: onto line_edge at edge_parameter
    Eigen::Vector3d barycentric;
    double edge_parameter;  ///< from line_edge[0], when new_triangle is -1
  };
  struct PolylineEdit {
    Index target_edge;
    std::vector<PolylinePoint> points;      ///< the whole polyline after the step
    std::uint32_t version_at_planning = 0;  ///< the polyline's edit count when it was copied
  };
  std::vector<Relocation> relocations;
  std::vector<PolylineEdit> polyline_edits;
  Index triangle_count_at_planning = 0;
  PlanExtent extent = PlanExtent::full;
  /// For an accepted ranking bound: the planning call that made it (per thread), so that a full
  /// plan asked for right after it, with the bound as `storage`, continues from it.
  std::uint64_t bound_generation = 0;

  /// For node_on_new_edge: the diagonal (ring indices of sheet blocking_sheet) the node would
  /// lie on, if it is one; for edge_along_new_edge: the diagonal an S2 edge's preimage would run
  /// along, if it is one; for fold_over: a diagonal of the new triangle that folds, if it has
  /// one. A caller may re-triangulate that sheet without it.
  std::array<int, 2> blocking_diagonal{-1, -1};
  int blocking_sheet = -1;

  bool accepted() const { return refusal == RemovalRefusal::none; }

  /// Empties the plan (as default-constructed) but keeps its buffers for the next plan.
  void reset();
  /// Polyline edits of an earlier plan, emptied, whose buffers the next cut reuses.
  std::vector<PolylineEdit> spare_edits;
};

class EditableMap {
 public:
  /// The identity map of `target` onto itself: S1 = S2.
  explicit EditableMap(std::shared_ptr<const Surface<2>> target, EditOptions options = {});
  ~EditableMap();
  EditableMap(EditableMap&&) noexcept;
  EditableMap& operator=(EditableMap&&) noexcept;

  const Surface<2>& target() const;
  const EditOptions& options() const;

  Index live_vertex_count() const;
  Index live_triangle_count() const;
  bool is_live_vertex(Index v) const;
  /// Live S1 triangles around S1 vertex v.
  std::span<const Index> vertex_triangles(Index v) const;
  /// S1 triangle ids run from 0 to triangle_slot_count() - 1; removed ones stay dead, new ones
  /// are appended.
  Index triangle_slot_count() const;
  bool is_live_triangle(Index t) const;
  const std::array<Index, 3>& triangle(Index t) const;
  /// True if S1 vertices a and b are joined by an edge of a live triangle.
  bool has_edge(Index a, Index b) const;
  /// Position of S1 vertex v (the position of S2 vertex v).
  const Eigen::Vector3d& position(Index v) const;

  /// The ring of v's star, counter-clockwise, if the star is one closed fan of consistently
  /// oriented triangles (an interior manifold vertex); empty otherwise.
  std::vector<Index> closed_ring(Index v) const;
  /// The sheets of the star of v on the feature line through its neighbours a and b (see
  /// StarSheet); empty if v's triangles do not split into fans from a to b, each consistently
  /// oriented.
  std::vector<StarSheet> line_star_sheets(Index v, Index a, Index b) const;

  /// Plans the removal of S1 vertex v given the flattened ring (one planar position per ring
  /// vertex, counter-clockwise around v at the origin; ring order as closed_ring(v)) and the
  /// triangulation of that polygon (triples of ring indices). Never changes the map.
  VertexRemovalPlan plan_vertex_removal(Index v, std::span<const Eigen::Vector2d> flattened_ring,
                                        std::span<const std::array<int, 3>> triangulation,
                                        PlanExtent extent = PlanExtent::full) const;
  /// The general form: plans the removal of v given its sheets (one closed sheet, or the open
  /// sheets of a vertex on a feature line), the flattening of each sheet and its triangulation.
  /// An open sheet's flattening puts its first ring vertex on the positive x axis, its last on
  /// the negative x axis (y exactly 0) and the others above; v is at the origin, so it lies on
  /// the new edge joining the line neighbours, and all sheets must place the line's nodes at the
  /// same parameters of that edge. The triangulation of an open sheet fills the polygon of its
  /// ring (closed by the new edge). The line's nodes (v and the nodes on the removed line edges)
  /// move onto the new edge.
  /// `storage`: a plan that is no longer needed, whose buffers the new plan reuses (a
  /// simplifier plans hundreds of thousands of times; allocating every vector anew cost a third
  /// of its time). Its contents do not change the result. One case is faster: a full plan of a
  /// closed star whose `storage` is the accepted ranking bound that the previous planning call on
  /// this thread made on this map, for the same star, flattening and triangulation, continues
  /// from that bound instead of relocating the star's preimages again (the same plan).
  VertexRemovalPlan plan_vertex_removal(Index v, std::span<const StarSheet> sheets,
                                        std::span<const std::vector<Eigen::Vector2d>> flattened,
                                        std::span<const std::vector<std::array<int, 3>>> triangulations,
                                        PlanExtent extent = PlanExtent::full, VertexRemovalPlan storage = {}) const;
  /// Carries out an accepted plan made on the current state.
  void apply(const VertexRemovalPlan& plan);
  /// Makes an accepted full plan of a closed star, made on an earlier state, applicable to the
  /// current one, if the removals since changed nothing it copied: v's star (the same live
  /// triangles), the S2 edge polylines it edits (each keeps an edit count), and no new S1 edge
  /// or triangle joins its ring vertices where the plan puts one. Then the plan is the one
  /// plan_vertex_removal would make now with the same flattening and triangulation (whether
  /// those would still be chosen is the caller's to know: they depend on which S1 edges join
  /// ring vertices). False, and the plan is unchanged, otherwise (and for feature-line plans).
  /// A simplifier that queues a vertex again after planning it fully keeps the plan for the
  /// next time the vertex comes up (a third of the full plans on CGAL's femur).
  bool refresh_plan(VertexRemovalPlan& plan) const;

  /// How much an accepted plan flattens the preimages of the S2 triangles at the vertex
  /// preimages it relocates: the smallest ratio, over those triangles, of the preimage's shape to
  /// the triangle's own (shape: 4 sqrt(3) area over the sum of squared sides, 1 for equilateral,
  /// 0 for degenerate), with the preimages where the plan puts them. 1 if it relocates nothing.
  /// A simplifier that perturbs a flattening to get past an exactly degenerate configuration
  /// checks with it that the plan did not just make that degeneracy slightly positive.
  double smallest_preimage_shape_ratio(const VertexRemovalPlan& plan) const;

  /// The S1 surface of the current state (live vertices renumbered in increasing order, live
  /// triangles) and, for each of its vertices, the S2 vertex it is.
  Surface<2> domain_surface(std::vector<Index>* domain_to_target_vertex = nullptr) const;
  /// The compact map Ξ: S1 → S2 of the current state, through MapBuilder (closure, finalize).
  /// With EditOptions::defer_cut, the S2 edges are traced first; throws DeferredCutFailure if
  /// the traced graph is not a valid parametrization.
  PlMap<2> to_map(BuilderOptions options = {}) const;

 private:
  struct Impl;
  struct Trace;  ///< the deferred cut's tracing (editable_map_trace.cpp)
  struct RemovalPlanning;  ///< one plan_vertex_removal call, phase by phase (removal_planning.hpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace plmap
