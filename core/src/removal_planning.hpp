#pragma once
// The state of one EditableMap::plan_vertex_removal call, shared by its phases (each in a file of
// its own, named after what it does):
//   editable_map_removal.cpp            entry points, the sheets' layout, the order of the phases
//   editable_map_removal_triangles.cpp  the star's triangles and the new triangles
//   editable_map_removal_relocation.cpp vertex preimages and the feature line's nodes move
//   editable_map_removal_fold.cpp       the deferred cut's straight-fold check
//   editable_map_removal_cut.cpp        every S2 edge polyline cut along the new edges
//   editable_map_removal_check.cpp      straightened pieces in one new triangle must not meet
// The per-thread buffers (PlanScratch) outlive the plan so that planning allocates nothing once
// warm; RemovalPlanning holds what the phases share by name (what were a lambda's captures).

#include "editable_map_state.hpp"

#include <Eigen/Geometry>

#include <limits>
#include <span>
#include <utility>

namespace plmap {

namespace removal {

using Vec2 = Eigen::Vector2d;

/// Barycentric coordinates of p in the planar triangle (a, b, c).
inline Eigen::Vector3d planar_barycentric(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  const double l1 = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
  const double l2 = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
  return {1.0 - l1 - l2, l1, l2};
}

/// A point of a polyline inside the star, with what it lies on in the new triangulation.
struct PlanarPoint {
  Vec2 position;
  Index corner = invalid_index;                             ///< S1 vertex it is, if any
  std::array<Index, 2> edge{invalid_index, invalid_index};  ///< S1 edge it lies on, if any
};

/// A straightened piece of an S2 edge's preimage inside one new triangle (planar).
struct Piece {
  int triangle;  ///< new triangle
  Vec2 from, to;
};

/// Where a planar segment of a polyline crosses a diagonal of its sheet.
struct Cut {
  double along;      ///< parameter on the segment
  int diagonal;
  double parameter;  ///< on the diagonal, from its first ring vertex
};

/// One sheet of the star during planning.
struct SheetPlan {
  const std::vector<Index>* ring = nullptr;
  std::span<const Vec2> flat;
  std::span<const std::array<int, 3>> triangulation;
  bool closed = true;
  int first_old = 0, first_new = 0;
  std::vector<std::array<int, 2>> diagonals;        ///< interior edges of the triangulation
  std::vector<Eigen::AlignedBox2d> diagonal_boxes;  ///< per diagonal, filled by the cut
  std::vector<std::pair<Index, Vec2>> moved;        ///< vertex preimages inside, planar

  int size() const { return static_cast<int>(ring->size()); }
  /// Triangles of the fan around v: an open sheet has none on its new line edge.
  int fan_size() const { return closed ? size() : size() - 1; }
  int ring_index(Index w) const {
    for (std::size_t i = 0; i < ring->size(); ++i)
      if ((*ring)[i] == w) return static_cast<int>(i);
    return -1;
  }
  /// The polygon's edges: consecutive ring vertices, and for an open sheet also its last and
  /// first vertex (the new line edge).
  bool adjacent(int i, int j) const {
    const int k = size();
    return (i + 1) % k == j || (j + 1) % k == i;
  }
  const Vec2* moved_position(Index w) const {
    for (const auto& [u, p] : moved)
      if (u == w) return &p;
    return nullptr;
  }
};

/// Working buffers of a plan that do not outlive it, kept per thread between plans (a
/// simplifier plans hundreds of thousands of times: none of them allocates once these are warm).
struct PlanScratch {
  std::vector<SheetPlan> sheets;
  std::vector<std::array<Index, 2>> new_edges;
  std::vector<Index> star_triangles, edges;
  /// Per S1 triangle slot: its place among the plan's old triangles, or -1; per S2 vertex: the
  /// sheet and place of its entry in that sheet's `moved`, or -1. Lookups the cut makes for
  /// every polyline point (a search of the star's lists each, quadratic in a late star's nodes);
  /// set per plan and reset by SlotReset, so they are -1 everywhere between plans.
  std::vector<int> star_slot;
  std::vector<std::array<int, 2>> moved_slot;
  std::vector<Index> marked_triangles, marked_vertices;
  /// The cut's buffers, reused for every polyline: the crossings of one segment, the planar
  /// points of one run through the star, and every straightened piece (for the check).
  std::vector<Cut> cuts;
  std::vector<PlanarPoint> run_points;
  std::vector<Piece> pieces;
  /// The check's order of the pieces (by new triangle, then by the left end of the x-range):
  /// per new triangle where its pieces start in `piece_order`, and each piece's left end.
  std::vector<int> piece_start, piece_order;
  std::vector<double> piece_left;
  /// The straight-fold check's unfolding of one sheet: per ring index, its position and whether
  /// it is placed yet.
  std::vector<Vec2> unfolded;
  std::vector<char> placed;
  /// The planning call (counted per thread) and the map of the last plan, and the flattening of
  /// its sheet if it ended as an accepted ranking bound: what plan_vertex_removal checks before
  /// a full plan continues from that bound.
  std::uint64_t generation = 0;
  const void* owner = nullptr;
  std::vector<Vec2> bound_flat;
};

/// Resets the slots a plan marked, on every way out of the plan.
struct SlotReset {
  PlanScratch& scratch;
  ~SlotReset() {
    for (Index t : scratch.marked_triangles) scratch.star_slot[static_cast<std::size_t>(t)] = -1;
    for (Index w : scratch.marked_vertices) scratch.moved_slot[static_cast<std::size_t>(w)] = {-1, -1};
    scratch.marked_triangles.clear();
    scratch.marked_vertices.clear();
  }
};

}  // namespace removal

/// One planning call: the map it plans on, the plan it fills, the per-thread buffers, and what
/// every phase needs to know of the star. Each phase returns RemovalRefusal::none to go on, or
/// why the removal is refused (the caller records it in the plan and stops).
struct EditableMap::RemovalPlanning {
  using Vec2 = removal::Vec2;

  const Impl& s;
  const Surface<2>& t2;  ///< S2, whose vertices are the nodes' images
  VertexRemovalPlan& plan;
  removal::PlanScratch& scratch;
  std::vector<removal::SheetPlan>& sheets;  ///< scratch.sheets: the first sheet_count are this plan's
  const Index v;
  const int sheet_count;
  /// On a feature line: the line neighbours of v (smaller first), joined by the new edge.
  const bool on_line;
  const std::array<Index, 2> line_key;
  const double clearance;  ///< EditOptions::edge_clearance
  const Vec2 origin = Vec2::Zero();  ///< where every sheet puts v

  // ---- phases, in the order plan_vertex_removal runs them, with their steps ----
  // editable_map_removal_triangles.cpp: the star's triangles, sheet by sheet, and the new ones
  RemovalRefusal collect_star_triangles(std::span<const StarSheet> star_sheets,
                                        std::span<const std::vector<Vec2>> flattened,
                                        std::span<const std::vector<std::array<int, 3>>> triangulations);
  RemovalRefusal collect_fan(int g);
  Index fan_triangle(Index x, Index y) const;
  RemovalRefusal check_flattening(int g) const;
  void mark_star_triangles();
  RemovalRefusal check_line_parameters() const;
  RemovalRefusal make_new_triangles();
  RemovalRefusal triangulate_sheet(int g, double area_scale);
  RemovalRefusal add_new_triangle(int g, const std::array<int, 3>& tri, const Eigen::Vector3d& sheet_normal,
                                  double area_scale);
  RemovalRefusal check_hole_triangle_is_new(int g) const;
  // editable_map_removal_relocation.cpp: vertex preimages into the new triangles, the line's
  // nodes onto the new edge
  RemovalRefusal relocate_preimages();
  void gather_moved_preimages(int g);
  void name_blocking_diagonal(int g, int n, const Eigen::Vector3d& b);
  RemovalRefusal move_line_nodes();
  void index_moved_preimages();
  // editable_map_removal_fold.cpp: with the deferred cut, the straight segments keep S2's
  // orientation
  RemovalRefusal check_straight_folds();
  void unfold_sheet(int g);
  Vec2 unfold(Index a, Index b, Index r, const Vec2& pa, const Vec2& pb, const Vec2& away) const;
  Vec2 unfolded_beyond(int g, Index t, int unknown, const std::array<int, 3>& at_ring) const;
  bool straight_point(int g, std::size_t relocation_base, Index w, Vec2& at) const;
  bool turns_over(int g, std::size_t relocation_base, Index w, const Vec2& pw, double margin) const;
  RemovalRefusal check_sheet_folds(int g, std::size_t relocation_base, double margin) const;
  // editable_map_removal_cut.cpp: every S2 edge polyline through the star, cut along the new
  // triangles' interior edges
  RemovalRefusal cut_polylines();
  RemovalRefusal cut_polyline(Index e);
  std::pair<bool, int> triangle_along_kept_edge(const EdgePolyline& p) const;
  RemovalRefusal cut_run(const EdgePolyline& p, int first, int last, VertexRemovalPlan::PolylineEdit& edit);
  RemovalRefusal planar_points_of_run(int g, const EdgePolyline& p, int first, int last);
  RemovalRefusal find_cuts(int g, const removal::PlanarPoint& from, const removal::PlanarPoint& to);
  const Vec2* moved_position(int g, Index w) const;
  bool vertex_point(int g, Index w, removal::PlanarPoint& q) const;
  std::array<Index, 2> common_edge(Index w1, Index w2) const;
  int new_triangle_with(int g, Index a, Index b) const;
  void name_diagonal(int g, Index a, Index b);
  RemovalRefusal along_diagonal(int g, int d);
  // editable_map_removal_check.cpp: straightened pieces in one new triangle do not meet
  RemovalRefusal check_pieces();

  // ---- what several phases ask ----
  const Eigen::Vector3d& position(Index w) const { return t2.vertex(w); }
  /// The place of S1 triangle t among the plan's old triangles, or -1 if it is not in the star.
  int star_position(Index t) const { return scratch.star_slot[static_cast<std::size_t>(t)]; }
  /// Planar position in sheet g of v or a ring vertex w.
  Vec2 planar_corner(int g, Index w) const {
    return w == v ? origin : sheets[g].flat[sheets[g].ring_index(w)];
  }
  /// Where planar point p of sheet g projects onto the new line edge (0 at line_key[0]).
  double line_parameter(int g, const Vec2& p) const {
    const Vec2 from = planar_corner(g, line_key[0]), to = planar_corner(g, line_key[1]);
    return (p.x() - from.x()) / (to.x() - from.x());
  }
  /// Where a planar point of sheet g falls among the sheet's new triangles: the new triangle
  /// (plan index) that holds it best and the smallest barycentric coordinate there.
  std::pair<int, double> locate(int g, const Vec2& p, Eigen::Vector3d* barycentric) const {
    const removal::SheetPlan& sh = sheets[g];
    int best = -1;
    double best_min = -std::numeric_limits<double>::infinity();
    for (int n = 0; n < sh.size() - 2; ++n) {
      const auto& tri = sh.triangulation[n];
      const Eigen::Vector3d b = removal::planar_barycentric(sh.flat[tri[0]], sh.flat[tri[1]], sh.flat[tri[2]], p);
      if (b.minCoeff() > best_min) {
        best_min = b.minCoeff();
        best = n;
        if (barycentric) *barycentric = b;
        // Inside by more than the clearance: the new triangles do not overlap, so no other one
        // can hold the point with all coordinates above it (rounding is far below 1e-9).
        if (best_min > std::max(clearance, 1e-9)) break;
      }
    }
    return std::pair{best < 0 ? -1 : sh.first_new + best, best_min};
  }
  /// The point with barycentric coordinates b on new triangle n, in space.
  Eigen::Vector3d world_on_new(int n, const Eigen::Vector3d& b) const {
    const auto& c = plan.new_triangles[n];
    return Eigen::Vector3d(b(0) * position(c[0]) + b(1) * position(c[1]) + b(2) * position(c[2]));
  }
  /// A node that moved or was created: where it lies on the new triangles and its image on S2.
  void record_node(const Eigen::Vector3d& domain, const Eigen::Vector3d& image) {
    plan.node_domain_positions.push_back(domain);
    plan.node_target_positions.push_back(image);
    plan.max_node_distance = std::max(plan.max_node_distance, (domain - image).norm());
  }
  /// Distance from v along the removed line edge (v, end) of S2 vertex w on it.
  double spoke_fraction(Index w) const {
    const double t = s.preimage_edge_parameter[w];
    return s.preimage_edge[w][0] == v ? t : 1.0 - t;
  }
  /// The line end whose removed edge S2 vertex w lies on, or invalid.
  Index line_end_of(Index w) const {
    if (!on_line || !s.on_edge(w)) return invalid_index;
    for (Index end : line_key)
      if (s.preimage_edge[w] == sorted_pair(v, end)) return end;
    return invalid_index;
  }
  /// The largest coordinate of any sheet's flattening: the star's size, which scales the
  /// clearance into a planar margin.
  double star_size() const {
    double size = 0.0;
    for (int g = 0; g < sheet_count; ++g)
      for (const Vec2& corner : sheets[g].flat) size = std::max(size, corner.cwiseAbs().maxCoeff());
    return size;
  }
};

}  // namespace plmap
