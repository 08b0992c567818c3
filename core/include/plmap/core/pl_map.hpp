#pragma once
/// \file
/// PlMap<d>: the finalized, compact form of a piecewise-linear map Xi: D ⊂ S1 -> S2.
///
/// The map is stored as the preimage of S2's edge graph on S1 (paper section 2.2): on every S1
/// element a plane graph of nodes whose regions (after the triangular closure) are triangles
/// (d = 2) or intervals (d = 1). Everything lives in flat arrays grouped by S1 element, so a
/// query touches a few contiguous cache lines and no per-node heap allocation exists.
///
/// A PlMap is immutable. It is produced by MapBuilder::finalize() or by loading a map file; the
/// raw arrays (MapData) are public so that verify/ can inspect them and tests can corrupt them.
///
/// What is stored and what is derived (docs/data-model.md): a triangle map (d = 2) stores the
/// nodes and the regions with their affine maps, everything evaluation reads. The graph arrays
/// that only graph walkers read — neighbour lists with their edge kinds, edge arrays, region
/// neighbours — follow from the regions and are derived on first use (data(), neighbors(),
/// edge_nodes(), region_neighbors()), except on the elements that store them (StoredGraph):
/// those the regions do not tile (parts outside D, dangling edge pieces). MapBuilder and the
/// binary file hand over exactly that stored form, so building or loading a map derives and
/// compares nothing; a map handed its full arrays (the text file, a hand-made map) has each
/// element's graph compared with the derivation once and keeps it where they differ, so
/// data() gives back what it was handed. Segment maps (d = 1) store everything.

#include <plmap/core/map_provenance.hpp>
#include <plmap/core/node_type.hpp>
#include <plmap/core/surface.hpp>
#include <plmap/core/types.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

namespace plmap {

/// y = A x + b between local coordinates, stored as the d x (d+1) matrix [A | b].
template <int d>
using AffineMap = Eigen::Matrix<double, d, d + 1>;

template <int d>
LocalPoint<d> apply(const AffineMap<d>& m, const LocalPoint<d>& x) {
  return m.template leftCols<d>() * x + m.col(d);
}

/// Whether a graph edge is the preimage of (a piece of) an S2 edge, or was added by the
/// triangular closure (including pieces of the S1 element boundary).
enum class GraphEdgeKind : std::uint8_t { closure = 0, target_edge = 1 };

/// The raw arrays of a finalized map. Index conventions:
/// - Nodes are numbered globally; the nodes of S1 element T are [node_begin[T], node_begin[T+1]).
///   A node on a shared corner or edge has one copy (one index) per incident element.
/// - Regions are numbered globally; those of T are [region_begin[T], region_begin[T+1]).
/// - All node indices stored in neighbour lists, edge arrays and region corners refer to nodes
///   of the same element.
template <int d>
struct MapData {
  // ---- nodes -------------------------------------------------------------------------------
  std::vector<Index> node_begin;            ///< size |T1| + 1
  std::vector<LocalPoint<d>> node_position;  ///< local coordinates on the S1 element
  std::vector<NodeType> node_type;
  /// For corner and ghost nodes the corner of the element (0..d), for touching and intersection
  /// nodes the local edge (0..2), for interior nodes -1.
  std::vector<std::int8_t> node_location;
  /// Image on S2: an S2 element (any element containing the point) and local coordinates on it,
  /// read together through node_image(n). Two arrays rather than one of SurfacePoint<d>: that
  /// struct pads its 4-byte element to the 16-byte alignment of the local point, 12 of its 32
  /// bytes per node for d = 2 (docs/data-model.md).
  std::vector<Index> node_image_element;
  std::vector<LocalPoint<d>> node_image_local;
  /// The S2 vertex of corner, touching and interior nodes; the S2 edge of intersection nodes;
  /// invalid_index for ghost nodes.
  std::vector<Index> node_target;

  // ---- neighbours in counter-clockwise order (d = 1: by increasing position) ------------------
  std::vector<Index> neighbor_begin;  ///< size node count + 1
  std::vector<Index> neighbor;
  std::vector<GraphEdgeKind> neighbor_edge_kind;

  // ---- d = 2: nodes on the closed local edges, ordered from corner k to corner (k+1) mod 3 ----
  std::vector<Index> edge_node_begin;  ///< size 3 |T1| + 1, entry 3T + k
  std::vector<Index> edge_node;

  // ---- regions (triangles for d = 2, intervals for d = 1) -------------------------------------
  std::vector<Index> region_begin;  ///< size |T1| + 1
  /// Corners (node indices), counter-clockwise on the S1 element (d = 1: increasing position).
  std::vector<std::array<Index, d + 1>> region_corners;
  /// Region across the side opposite corner i on the same element, or invalid_index.
  std::vector<std::array<Index, d + 1>> region_neighbors;
  /// The S2 element all corners map into.
  std::vector<Index> region_target;
  /// Local coordinates on the S1 element -> local coordinates on region_target.
  std::vector<AffineMap<d>> region_map;
  /// Per S1 element: the region a point-location walk starts from (invalid if no regions).
  std::vector<Index> start_region;

  /// +1 if the map preserves the orientation of the element frames, -1 if it reverses it (as for
  /// two bodies in contact whose normals face each other).
  int orientation = 1;

  /// The image of node n on S2 (node_image_element and node_image_local put together).
  SurfacePoint<d> node_image(Index n) const { return {node_image_element[n], node_image_local[n]}; }

  friend bool operator==(const MapData&, const MapData&) = default;
};

/// The graph arrays of the elements of a triangle map that store them (see PlMap), element by
/// element in increasing order; indices are global, as in MapData.
struct StoredGraph {
  std::vector<Index> element;
  std::vector<Index> neighbor_count;  ///< per node of these elements
  std::vector<Index> neighbor;
  std::vector<GraphEdgeKind> neighbor_edge_kind;
  std::vector<Index> edge_node_count;  ///< three per element
  std::vector<Index> edge_node;
  std::vector<std::array<Index, 3>> region_neighbors;  ///< per region of these elements
  /// Whether it is known that every element here needs its graph (its regions do not give it
  /// back), so that a change of other elements need not derive these again (remove_regions,
  /// clip_regions). False where nobody checked: MapBuilder hands over some graphs that the
  /// regions would give back (the first removal drops them), and a file does not record it.
  /// What is known of the graph, not part of it: == does not compare it.
  bool known_minimal = false;
  friend bool operator==(const StoredGraph& a, const StoredGraph& b) {
    return a.element == b.element && a.neighbor_count == b.neighbor_count && a.neighbor == b.neighbor &&
           a.neighbor_edge_kind == b.neighbor_edge_kind && a.edge_node_count == b.edge_node_count &&
           a.edge_node == b.edge_node && a.region_neighbors == b.region_neighbors;
  }
};

template <int d>
  requires SurfaceDimension<d>
class PlMap {
 public:
  static constexpr int dimension = d;

  /// Takes ownership of the arrays; throws InvalidMapError if their sizes do not fit the
  /// surfaces or an index is out of range (a cheap structural check). Loading a file also runs
  /// validate_map_structure (map_validation.hpp); verify/ does the full check.
  PlMap(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
        MapData<d> data);
  /// A triangle map in its stored form: `stored` without the graph arrays (they must be empty),
  /// `graph` the graph arrays of the elements that keep them; every other element's graph is
  /// derived on first use. Nothing is compared: this is how MapBuilder and the binary file hand
  /// a map over. Throws InvalidMapError like the constructor above.
  PlMap(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
        MapData<d> stored, StoredGraph graph)
    requires(d == 2);
  PlMap(const PlMap& other);
  PlMap& operator=(const PlMap& other);
  PlMap(PlMap&&) noexcept = default;
  PlMap& operator=(PlMap&&) noexcept = default;
  ~PlMap();

  const Surface<d>& domain() const { return *domain_; }
  const Surface<d>& target() const { return *target_; }
  const std::shared_ptr<const Surface<d>>& domain_ptr() const { return domain_; }
  const std::shared_ptr<const Surface<d>>& target_ptr() const { return target_; }
  /// All arrays, the derived graph arrays included (derived on the first call; thread-safe).
  const MapData<d>& data() const;
  /// The arrays the map stores, without deriving anything: what evaluation reads. The graph
  /// arrays (neighbor_begin, neighbor, neighbor_edge_kind, edge_node_begin, edge_node,
  /// region_neighbors) are empty here for d = 2 unless data() or region_neighbors() has derived
  /// them; read those through data(), neighbors(), edge_nodes() or region_neighbors().
  const MapData<d>& stored() const { return data_; }
  /// Region across the side opposite corner i of each region, or invalid_index (derived on the
  /// first call for d = 2; thread-safe). Walking point locators read it.
  std::span<const std::array<Index, d + 1>> region_neighbors() const;
  /// Gives up the arrays (this map is left empty), e.g. to attach them to similar copies of the
  /// surfaces: the arrays hold only local and barycentric coordinates, which a similarity keeps.
  MapData<d> release_data() &&;
  /// Gives up the stored form of a triangle map (this map is left empty): the stored arrays,
  /// without any graph arrays derived into them, and the stored graph, as the stored-form
  /// constructor takes them. Nothing is derived (unlike release_data()).
  std::pair<MapData<d>, StoredGraph> release_stored_form() &&
    requires(d == 2);

  Index node_count() const { return static_cast<Index>(data_.node_type.size()); }
  Index region_count() const { return static_cast<Index>(data_.region_target.size()); }
  Index nodes_begin(Index element) const { return data_.node_begin[element]; }
  Index nodes_end(Index element) const { return data_.node_begin[element + 1]; }
  Index regions_begin(Index element) const { return data_.region_begin[element]; }
  Index regions_end(Index element) const { return data_.region_begin[element + 1]; }

  /// Neighbours of node n in counter-clockwise order.
  std::span<const Index> neighbors(Index n) const {
    const MapData<d>& m = data();
    return {m.neighbor.data() + m.neighbor_begin[n], m.neighbor.data() + m.neighbor_begin[n + 1]};
  }
  /// Nodes on local edge k of element t, from corner k to corner (k+1) mod 3 (d = 2).
  std::span<const Index> edge_nodes(Index t, int k) const
    requires(d == 2)
  {
    const std::size_t i = 3 * static_cast<std::size_t>(t) + k;
    const MapData<d>& m = data();
    return {m.edge_node.data() + m.edge_node_begin[i], m.edge_node.data() + m.edge_node_begin[i + 1]};
  }

  /// World position of node n on S1 and of its image on S2.
  WorldPoint<d> node_domain_world(Index n) const;
  WorldPoint<d> node_target_world(Index n) const;
  /// S1 element that owns node n (binary search on node_begin).
  Index node_element(Index n) const;

  /// Bytes the map stores (capacity of its flat arrays, not counting the two surfaces nor the
  /// derived graph arrays).
  std::size_t memory_bytes() const;
  /// Bytes of the graph arrays derived so far (0 until data() or region_neighbors() is called).
  std::size_t derived_bytes() const;
  /// How many elements store their graph arrays because the derivation does not give them back.
  Index elements_with_stored_graph() const {
    return static_cast<Index>(stored_graph_.element.size());
  }
  /// The graph arrays of the elements that store them (empty for d = 1, which stores all of
  /// them in stored()).
  const StoredGraph& stored_graph() const { return stored_graph_; }

  /// How the map was made (map_provenance.hpp): empty unless its maker recorded something, as
  /// normal projection records its acceptance rules (projection_rules.hpp). Saved and loaded with
  /// the map in both file formats, and kept by copies and moves of the map.
  const MapProvenance& provenance() const { return provenance_; }
  /// Replaces the provenance; throws InvalidMapError if an entry is not a pair of tokens.
  void set_provenance(MapProvenance provenance);

 private:
  /// The cheap structural checks of the arrays every map stores (sizes, ranges of the indices
  /// that queries dereference), and of the stored graph.
  void check_stored_arrays() const;
  void check_stored_graph() const;
  /// Checks element by element that the graph arrays follow from the regions; releases them and
  /// keeps (in stored_graph_) only those of the elements where they do not.
  void keep_only_underived_graph();
  void derive_region_neighbors() const;
  void derive_graph() const;

  std::shared_ptr<const Surface<d>> domain_;
  std::shared_ptr<const Surface<d>> target_;
  /// The stored arrays; the derived graph arrays are written into it once, under the flags.
  mutable MapData<d> data_;
  StoredGraph stored_graph_;
  MapProvenance provenance_;
  struct DerivationFlags {
    std::once_flag region_neighbors, graph;
    // set after the call_once above, so that the walks' per-query check is one load
    std::atomic<bool> region_neighbors_ready{false}, graph_ready{false};
  };
  std::unique_ptr<DerivationFlags> derived_ = std::make_unique<DerivationFlags>();
};

extern template class PlMap<1>;
extern template class PlMap<2>;

}  // namespace plmap
