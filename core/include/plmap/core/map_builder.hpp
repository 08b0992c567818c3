#pragma once
/// \file
/// MapBuilder<d>: the factory of paper section 3.1, the mutable form of a map.
///
/// Usage (d = 2):
///   MapBuilder<2> b(s1, s2);
///   for each S2 vertex v with a preimage:   b.add_vertex_preimage(v, {element, local});
///   for each S1 vertex w not on an S2 vertex: b.add_ghost_node(w, {s2_element, s2_local});
///   for each S2 edge e:  b.add_edge(e)                      (preimage inside one S1 element)
///                    or  b.add_edge(e, crossings)           (preimage crosses S1 edges)
///   or simply b.add_target_element(t) for S2 triangles whose edges stay inside S1 elements;
///   PlMap<2> map = std::move(b).finalize();
///
/// Nodes on S1 vertices and edges are entered once and copied onto every incident element at
/// finalize(). Positions closer than `BuilderOptions::snap_tolerance` (in local coordinates, hence
/// relative to the element size) to a corner or an edge are snapped there, by the single
/// snapping rule of plmap (core/snapping.hpp).
///
/// finalize() computes, per S1 element, the triangular closure of the plane graph formed by the
/// graph edges and the element boundary: it traces the graph's faces (edges ordered around each
/// node by exact orientation predicates) and cuts each face into triangles, falling back to a
/// constrained Delaunay triangulation where the graph is not a plain tiling (e.g. a part floating
/// inside a face). It keeps the faces that map into one S2 element with the map's orientation as
/// regions, derives each node's cyclic neighbour order by circulating the triangles around it
/// (combinatorial; no angles are computed), builds the edge arrays and the compact query form.
/// Elements are closed in parallel when BuilderOptions::threads asks for it.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace plmap {

struct BuilderOptions {
  /// Local coordinates within this distance of a corner or edge are snapped onto it. Also the
  /// threshold below which an image barycentric coordinate on S2 is set to zero.
  double snap_tolerance = 1e-10;
  /// Orientation of the map: 0 = decide by majority of the candidate regions (default),
  /// +1 = orientation preserving, -1 = orientation reversing.
  int orientation = 0;
  /// Threads finalize() uses for the per-element triangular closure (0: all cores). The result
  /// does not depend on it.
  unsigned threads = 1;
  /// What finalize() does when the preimages of S2 edges cross on an S1 element, or one passes
  /// through a node (inconsistent input, e.g. a projection that folds): false (default) throws
  /// BuilderError naming the element; true drops, for every S2 edge involved, the stretch of its
  /// preimage on that element (d = 1: the whole S2 segment) and lists the edge in the
  /// FinalizeReport. The rest of the preimage stays, ending at the element's boundary as a piece
  /// does (add_edge_piece); faces next to a dropped stretch are not regions.
  bool drop_conflicting_edges = false;
  /// d = 2: what finalize() does with a face whose nodes map into no one S2 element (the
  /// preimage of an S2 edge that would split it is missing in part: FinalizeReport::unmapped_faces).
  /// false (default): the face leaves D. true: each triangle of its closure whose three corners map
  /// into one S2 element with the map's orientation stays, as a region of that element; the rest
  /// leaves D. The same holds for a face at an S1 corner without a node (outside D's reach as a
  /// whole): its triangles that do not touch that corner are judged alike. Such regions are
  /// continuous with each other and with the faces around them, but their images are not bounded
  /// by their S2 element's edges and may overlap another part of the map's image: the caller
  /// must check the elements listed in FinalizeReport::split_targets (the projection compares
  /// them with keep_nearer_sheet, which is why it sets this only then).
  bool split_unmapped_faces = false;
  /// d = 2: room the finished map's node and region arrays keep beyond their sizes, as a
  /// fraction of them (plus 1,024 entries): address space only, never written, so it costs no
  /// resident memory (PlMap::memory_bytes, which counts capacity, shows it). An operation that
  /// then adds nodes and regions in place (clip_regions, core/region_clipping.hpp) needs no second
  /// copy of the arrays, which would raise the peak by the largest of them. 0 (default): none.
  double spare_room = 0.0;
  /// d = 2: finalize() also measures the finished regions' images (FinalizeReport::images), from
  /// the images it computes their affine maps from, so that a caller that needs the measures
  /// (the projection's fold and sheet tests) need not measure the map again. false (default): not
  /// measured.
  bool measure_images = false;
};

/// What finalize() had to leave out.
struct FinalizeReport {
  /// S2 edges of which a stretch was dropped (drop_conflicting_edges; d = 1: the whole segment),
  /// each once
  std::vector<Index> dropped_edges;
  std::vector<Index> dropped_edge_element;  ///< for each, the first S1 element where it conflicted
  /// Faces of the graph (d = 1: pieces between two nodes) that map into one S2 element but
  /// with the orientation opposite to the map's, or onto a degenerate image: they are not
  /// regions, so D has a hole there (the projection is folded).
  Index reversed_faces = 0;
  /// Faces of the graph (d = 2) with every corner of theirs inside D's reach, whose nodes map
  /// into no one S2 element: the preimage of an S2 edge that would split them is missing (a walk
  /// stopped or left it out), so they are not regions and D has a hole there. 0 in a map whose
  /// graph is complete. Where reversed or unmapped faces would leave a hole strictly inside an
  /// element whose boundary the regions cover (not a hole of S2), the whole element leaves D:
  /// such an element must be covered entirely (verify's region_tiling, face_removal.hpp).
  Index unmapped_faces = 0;
  /// d = 2: the measure of S1 that finalize() leaves out of D, by why (finalize_reusing counts
  /// only the elements it closes, not those it copies). With the measure D covers, these add up
  /// to S1's measure.
  struct MeasureLeftOut {
    /// Beyond D's reach: faces that touch an S1 corner without a node (its ray found no
    /// admissible image), and elements that nothing of the map reaches.
    double outside = 0.0;
    double reversed = 0.0;  ///< the reversed faces
    double unmapped = 0.0;  ///< the unmapped faces
    /// The regions of elements that left D whole because their reversed or unmapped faces lay
    /// strictly inside them (see unmapped_faces).
    double enclosed = 0.0;
    MeasureLeftOut& operator+=(const MeasureLeftOut& o) {
      outside += o.outside;
      reversed += o.reversed;
      unmapped += o.unmapped;
      enclosed += o.enclosed;
      return *this;
    }
  };
  MeasureLeftOut left_out;
  /// d = 2: the S2 elements that regions split off unmapped faces (or faces at a corner without
  /// a node) map into (sorted, each once).
  /// Such a region's image is not bounded by preimages of its S2 element's edges, so unlike a
  /// face's it can overlap the image of another part of S1 (see image_overlaps.hpp).
  std::vector<Index> split_targets;
  /// d = 2: the regions (sorted) split off faces at an S1 corner without a node, numbered as in
  /// the map finalize() returns. Their corners are nodes the walks reached around that corner,
  /// and nothing inserted between them vouches for the inside (the caller may test it, as the
  /// projection does against its rays).
  std::vector<Index> regions_split_off_outside_faces;
  /// d = 2, with BuilderOptions::measure_images: image_measures() of the map finalize() returns
  /// (covered.domain to the last bit; covered.target and per_target to rounding, the images taken
  /// as the region maps take them). Empty otherwise, and from finalize_reusing.
  std::optional<ImageMeasures> images;
};

/// Where the preimage of an S2 edge crosses an S1 edge (d = 2).
struct EdgeCrossing {
  Index domain_edge = invalid_index;  ///< the S1 edge crossed
  /// Position on the S1 edge, 0 at its smaller-index vertex and 1 at the larger. A value within
  /// the snap tolerance of 0 or 1 means the preimage passes through that S1 vertex; a ghost node
  /// is created there unless one exists.
  double domain_parameter = 0.5;
  /// Position of the image on the S2 edge (0 at its smaller-index vertex). NaN (the default):
  /// chosen proportional to the arc length of the preimage polyline in world coordinates.
  double target_parameter = std::numeric_limits<double>::quiet_NaN();
};

/// Where the preimage of an S2 segment passes an S1 vertex (d = 1).
struct VertexCrossing {
  Index domain_vertex = invalid_index;
  /// Position of the image on the S2 segment (0 at its first corner); NaN: by arc length.
  double target_parameter = std::numeric_limits<double>::quiet_NaN();
};

/// Where a piece of an S2 edge's preimage starts (MapBuilder::add_edge_piece).
enum class PieceStart : std::uint8_t {
  first_vertex,    ///< at the preimage of the edge's first vertex
  first_crossing,  ///< at the first crossing given (e.g. where the edge enters S1 across ∂S1)
  rim_node,        ///< at a rim node (MapBuilder::add_rim_node), before the first crossing given
};

/// Where a piece of an S2 edge's preimage ends (MapBuilder::add_edge_piece).
enum class PieceEnd : std::uint8_t {
  second_vertex,  ///< at the preimage of the edge's second vertex
  last_crossing,  ///< at the last crossing given (∂S1, or where the projection stops being defined)
  rim_node,       ///< at a rim node (MapBuilder::add_rim_node), after the last crossing given
};

/// The rim nodes a piece starts and ends at, for PieceStart::rim_node and PieceEnd::rim_node
/// (unused otherwise).
struct PieceRimNodes {
  Index start = invalid_index;
  Index end = invalid_index;
};

template <int d>
  requires SurfaceDimension<d>
class MapBuilder {
 public:
  /// Handle of a node entered into the builder (not of its per-element copies).
  using NodeHandle = Index;

  MapBuilder(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
             BuilderOptions options = {});
  ~MapBuilder();
  MapBuilder(MapBuilder&&) noexcept;
  MapBuilder& operator=(MapBuilder&&) noexcept;

  const Surface<d>& domain() const;
  const Surface<d>& target() const;

  /// The preimage of S2 vertex `target_vertex` is the point `at` of S1. Becomes a corner,
  /// touching (d = 2) or interior node depending on where `at` lies after snapping.
  NodeHandle add_vertex_preimage(Index target_vertex, const SurfacePoint<d>& at);
  /// The preimage of S2 vertex `target_vertex` is S1 vertex `domain_vertex` (a corner node).
  NodeHandle add_vertex_preimage_at_vertex(Index target_vertex, Index domain_vertex);
  /// The preimage of `target_vertex` lies on S1 edge `domain_edge` at parameter t (0 at its
  /// smaller-index vertex). d = 2 only.
  NodeHandle add_vertex_preimage_on_edge(Index target_vertex, Index domain_edge, double t)
    requires(d == 2);

  /// S1 vertex `domain_vertex` maps to `image` on S2, which is not an S2 vertex (a ghost node).
  /// If `image` snaps onto an S2 vertex that has no preimage yet, a corner node is made instead.
  NodeHandle add_ghost_node(Index domain_vertex, const SurfacePoint<d>& image);

  /// Inserts the preimage of S2 edge `target_edge` (d = 2), which lies in one S1 element or
  /// along one S1 edge: the preimages of both its vertices must exist.
  void add_edge(Index target_edge)
    requires(d == 2);
  /// Inserts the preimage of S2 edge `target_edge` that crosses the given S1 edges, listed in
  /// order from the preimage of the edge's smaller-index vertex to the larger.
  void add_edge(Index target_edge, std::span<const EdgeCrossing> crossings)
    requires(d == 2);
  /// Inserts the preimage of S2 segment `target_element` (d = 1), passing the listed S1
  /// vertices in order from the preimage of its corner 0 to corner 1.
  void add_edge(Index target_element, std::span<const VertexCrossing> crossings = {})
    requires(d == 1);

  /// Inserts a piece of an S2 edge's preimage where the map is defined on only part of the edge
  /// (it leaves S1 through S1's boundary, or D ends inside S1, e.g. where a projection folds):
  /// the piece starts at the preimage of the edge's first vertex or at crossings.front(), and
  /// ends at the preimage of the second vertex or at crossings.back(). A piece that ends at a
  /// crossing inside S1 leaves the faces beyond that crossing without one common S2 element, so
  /// they are not regions: D ends there. Crossings are in order from the first vertex's side,
  /// and every crossing must give its target_parameter. An S2 edge may consist of several
  /// disjoint pieces.
  /// A piece may also start or end at a rim node inside an S1 element (PieceStart::rim_node,
  /// PieceEnd::rim_node, the nodes given in `rims`), whose image must lie on this edge: D then
  /// ends there, on the rim, instead of at the last S1 edge crossed.
  void add_edge_piece(Index target_edge, std::span<const EdgeCrossing> crossings, PieceStart start, PieceEnd end,
                      PieceRimNodes rims = {})
    requires(d == 2);
  void add_edge_piece(Index target_element, std::span<const VertexCrossing> crossings, PieceStart start,
                      PieceEnd end)
    requires(d == 1);
  /// A node on the rim of D inside S1 (d = 2): a point of S1 where the map stops (a projection
  /// reaches its distance limit or a focal point), mapped to `image`, which is no S2 vertex.
  /// Snapped like every node: on an S1 vertex it is a ghost node (an existing ghost node there is
  /// returned), on an S1 edge a rim_on_edge node, inside an element a rim_inside node. A piece of
  /// an S2 edge ends at it where the image lies on that edge (add_edge_piece with
  /// PieceEnd::rim_node), and rim edges (add_rim_edge) join it to its neighbours along the rim.
  NodeHandle add_rim_node(const SurfacePoint<d>& at, const SurfacePoint<d>& image)
    requires(d == 2);
  /// A straight piece of the rim of D between two nodes of one S1 element (rim nodes, ghost nodes,
  /// or the nodes where pieces end): no S2 edge's preimage, but a side of the regions next to it
  /// (GraphEdgeKind::closure). The part of the element beyond it must be closed off by other rim
  /// edges, pieces ending inside S1, or corners without a node, so that it forms no region.
  void add_rim_edge(NodeHandle a, NodeHandle b)
    requires(d == 2);

  /// Declares that no part of S2 edge `target_edge` (d = 2) / segment (d = 1) lies over D (e.g.
  /// it lies beyond S1's boundary), so that the regions of S2 elements having such an edge are
  /// formed from the pieces of their other edges and S1's boundary. has_edge() stays false.
  void add_edge_outside_domain(Index target_edge);
  /// Inserts the edges of S2 element `target_element` that are not present yet; each must lie
  /// in one S1 element (use add_edge with crossings otherwise).
  void add_target_element(Index target_element);

  /// Node handle of the preimage of an S2 vertex, if entered.
  std::optional<NodeHandle> vertex_preimage(Index target_vertex) const;
  /// True if the preimage of this S2 edge (d = 2) / segment (d = 1) was inserted.
  bool has_edge(Index target_edge) const;

  /// Builds the compact map. The builder is left empty. `report`, if given, receives what had
  /// to be left out.
  PlMap<d> finalize(FinalizeReport* report = nullptr) &&;
  /// finalize(), copying each element t with reuse[t] != 0 from `previous` (a map on the same
  /// surfaces) instead of closing it again: the closure is most of finalize, and a caller that
  /// edits the graph of a few elements of a built map (smoothing's repeated quadrilateral pass)
  /// knows that the others are what they were. The caller guarantees that the graph entered on
  /// each reused element (its nodes, and the pieces of S2 edge preimages in it and along its
  /// edges) is the one `previous` was built from with the same options; then the result equals
  /// finalize()'s, array for array. A reused element is not checked again and counts no reversed
  /// faces; one whose node count differs from the entered graph's throws BuilderError. Needs the
  /// orientation given (BuilderOptions::orientation) and drop_conflicting_edges off.
  PlMap<d> finalize_reusing(const PlMap<d>& previous, std::span<const char> reuse, FinalizeReport* report = nullptr) &&
    requires(d == 2);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class MapBuilder<1>;
extern template class MapBuilder<2>;

}  // namespace plmap
