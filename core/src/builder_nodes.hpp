#pragma once
// What MapBuilder collects before finalize(), as finalize's phases read it: nodes at their places
// on S1 with their images as supports on S2, and the straight pieces of S2 edge preimages between
// them. Private to the builder (core/src).
//
// Every node is entered once, at its place on S1: an S1 vertex, a point of an S1 edge (parameter
// along the edge from its smaller-index vertex) or a point inside an S1 element. Its image is
// kept as a "support": the S2 vertices with non-zero barycentric weight. Supports make the
// question "which S2 elements contain this image?" exact and cheap, and they let an image be
// re-expressed on any of those elements without rounding.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/surface.hpp>
#include <plmap/core/types.hpp>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace plmap::detail {

enum class PlaceKind : std::uint8_t { vertex, edge, element };

/// A point of S1: a vertex, a point on an edge (d = 2; parameter from the smaller-index vertex),
/// or a point inside an element. The builder holds one per node (millions), so the parameter
/// and the local coordinates share storage, unaligned: a node takes 80 bytes instead of 96.
template <int d>
struct Place {
  using Coordinates = Eigen::Matrix<double, d, 1, Eigen::DontAlign>;
  Coordinates coords = Coordinates::Zero();  // kind == element: local; kind == edge: (t, 0)
  Index index = invalid_index;
  PlaceKind kind = PlaceKind::vertex;

  double t() const { return coords(0); }          // kind == edge
  LocalPoint<d> local() const { return coords; }  // kind == element
};

/// Image of a node on S2 as the S2 vertices carrying its barycentric weight. `element` contains
/// the image, so every support vertex is one of its corners: a vertex is kept as its corner
/// number there (two bits), not as an S2 vertex number. The builder holds one support per node
/// until finalize() has closed every element; three vertex numbers were 12 of a node's 72 bytes
/// (64 now: the femur pair's 46k nodes, 0.35 MiB of the projection's peak).
template <int d>
struct Support {
  std::array<double, d + 1> weight{};
  Index element = invalid_index;  // an S2 element containing the image (for the stored form)
  std::uint8_t count = 0;
  std::uint8_t corners = 0;  // support vertex i is corner corner(i) of element

  int corner(int i) const { return (corners >> (2 * i)) & 3; }
  Index vertex(const Surface<d>& s2, int i) const { return s2.element(element)[corner(i)]; }
  /// Appends corner c of `element` (0 .. d, not yet in the support) with weight w.
  void add(int c, double w) {
    corners = static_cast<std::uint8_t>(corners | (c << (2 * count)));
    weight[count++] = w;
  }
};

/// rim: a node on the rim of D inside S1 (on an S1 edge or inside an element), where the map stops.
enum class BuilderNodeKind : std::uint8_t { vertex_preimage, ghost, intersection, rim };

/// The builder holds one per node until finalize() has closed every element, so its nodes are
/// part of projection's peak memory. The one-byte kinds of the place, the support and the node
/// would each take a padding slot of its own: `image` and `place` may lend their tail padding
/// ([[no_unique_address]]), and `kind` sits in the support's, so a node takes 64 bytes, not 72
/// (d = 2: −6.8 MiB of the 200k plane pair's peak at 80 -> 72).
template <int d>
struct BuilderNode {
  [[no_unique_address]] Support<d> image;
  BuilderNodeKind kind;
  Index target;  // S2 vertex / S2 edge / invalid
  [[no_unique_address]] Place<d> place;

  BuilderNode(const Place<d>& place_, BuilderNodeKind kind_, Index target_, const Support<d>& image_)
      : image(image_), kind(kind_), target(target_), place(place_) {}
};
static_assert(sizeof(BuilderNode<2>) <= 64 && sizeof(BuilderNode<1>) <= 48, "builder nodes are kept compact");

/// A straight piece of an S2 edge's preimage between two nodes: inside element `where`, or (d = 2)
/// along S1 edge `where`. A piece of the rim of D (MapBuilder::add_rim_edge) has target_edge
/// invalid_index.
/// One per piece, millions on large maps: `along_edge` takes one bit of `where`'s word (S1 has
/// fewer than 2^30 elements and edges), so a segment takes 16 bytes, not 20.
struct Segment {
  Index a, b;
  Index target_edge;
  bool along_edge : 1;
  Index where : 31;
};
static_assert(sizeof(Segment) == 16, "segments are kept compact");

/// The builder's node and segment arrays: the largest it keeps (hundreds of MiB on a million
/// triangles), grown push by push and read at random by the closure, on transparent huge pages
/// (huge_page_allocator.hpp): on the 200k planes this took a third of the projection's page
/// faults away. Curves (d = 1) too, since their finalize no longer keeps per-element copies of
/// the nodes (1M circles: insertion 1.2 -> 0.85 s, peak +2.3 MiB of 2 MiB granularity, far
/// below half of ContactMerge's now).
/// Only from 12 MiB (six huge pages) on, though: the arrays are reserved for what a map usually
/// holds (MapBuilder::Impl::reserve_expected_sizes), often three times what a small map uses, so
/// each ends in a partly written huge page that is resident in full (femur pair, 46k nodes, 58k
/// segments in 9.4 and 2.6 MiB reserved: 6 MiB resident for 4.2 MiB used, 1.9 MiB of the
/// projection's peak). Arrays that small are mostly within the reach of the TLB's 4 KiB entries
/// (1.5-2k second-level entries on current x86 cores). 16 MiB took the armadillo pair's segments
/// (14 MiB reserved) off huge pages too: 1.8k more page faults, and no less peak.
inline constexpr std::size_t builder_huge_page_min_bytes = std::size_t{12} << 20;
template <class T>
using BuilderArray = std::vector<T, HugePageAllocator<T, builder_huge_page_min_bytes>>;
template <int d>
using BuilderNodes = BuilderArray<BuilderNode<d>>;
template <int d>  // segments are the same for both dimensions; d keeps the builder's names uniform
using BuilderSegments = BuilderArray<Segment>;

/// MapBuilder's record per S2 edge (d = 2) or S2 element (d = 1) of how its preimage is in the
/// map: not at all, whole, in pieces (a walk stopped somewhere along it), or outside the domain.
inline constexpr char edge_not_inserted = 0, edge_complete = 1, edge_partial = 2, edge_outside_domain = 3;

/// What finalize() reads of the builder (and the little it changes: the nodes and segments are
/// released once every element is closed, and dropped S2 edges are marked as not inserted).
template <int d>
struct BuilderContents {
  const Surface<d>& s1;
  const Surface<d>& s2;
  const BuilderOptions& options;
  BuilderNodes<d>& nodes;
  const std::vector<Index>& node_at_domain_vertex;  // per S1 vertex: its node, or invalid_index
  BuilderSegments<d>& segments;
  std::vector<char>& edge_inserted;  // per S2 edge (d = 1: S2 element), 0: not inserted
};

/// What finalize() leaves out because preimages conflict (BuilderOptions::drop_conflicting_edges):
/// whole S2 edges (d = 1: their segments and the intersection nodes they created are not part of
/// the map), or (d = 2) the stretch of an S2 edge's preimage on one S1 element — its segments
/// inside the element and along its edges — while the rest of that preimage stays, ending at the
/// crossings on the element's boundary as a partly inserted edge does.
class DroppedEdges {
 public:
  DroppedEdges(std::vector<char>& edge_inserted, FinalizeReport* report, std::size_t segment_count = 0)
      : dropped_(edge_inserted.size(), 0), reported_(edge_inserted.size(), 0), segment_dropped_(segment_count, 0),
        edge_inserted_(edge_inserted), report_(report) {}
  bool contains(Index e) const { return dropped_[static_cast<std::size_t>(e)] != 0; }
  /// Whether segment s is left out: its S2 edge is dropped, or its stretch is (a rim edge, with
  /// no S2 edge, never is).
  bool drops_segment(Index s, Index target_edge) const {
    return (target_edge != invalid_index && contains(target_edge)) ||
           (!segment_dropped_.empty() && segment_dropped_[static_cast<std::size_t>(s)] != 0);
  }
  /// Drops S2 edge e, found in conflict on S1 element t, and reports it; false if it was dropped
  /// already.
  bool drop(Index e, Index t) {
    if (contains(e)) return false;
    dropped_[static_cast<std::size_t>(e)] = 1;
    changes_.whole_edges = true;
    edge_inserted_[static_cast<std::size_t>(e)] = edge_not_inserted;
    report(e, t);
    return true;
  }
  /// Drops the given segments (the stretch of S2 edge e on S1 element t) and reports e once;
  /// false if none of them was still in the map.
  bool drop_stretch(Index e, Index t, std::span<const Index> segments) {
    const bool any = drop_segments(segments);
    if (any) report(e, t);
    return any;
  }
  /// Drops rim edges (no S2 edge, nothing to report); false if none of them was still in the map.
  bool drop_rim_segments(std::span<const Index> segments) {
    const bool any = drop_segments(segments);
    rim_segments_dropped_ = rim_segments_dropped_ || any;
    return any;
  }
  /// Drops the given segments without a report; false if none of them was still in the map.
  bool drop_segments(std::span<const Index> segments) {
    bool any = false;
    for (Index s : segments) {
      char& flag = segment_dropped_[static_cast<std::size_t>(s)];
      if (flag == 0) changes_.segments.push_back(s);
      any = any || flag == 0;
      flag = 1;
    }
    return any;
  }
  /// Whether any rim edge was dropped (only then can a rim node be left without its rim).
  bool dropped_rim_segments() const { return rim_segments_dropped_; }
  /// Leaves rim node n out of the map (drop_rim_nodes_left_without_rim).
  void drop_rim_node(Index n, std::size_t node_count) {
    if (node_dropped_.empty()) node_dropped_.assign(node_count, 0);
    node_dropped_[static_cast<std::size_t>(n)] = 1;
    changes_.nodes.push_back(n);
  }
  bool drops_node(Index n) const { return !node_dropped_.empty() && node_dropped_[static_cast<std::size_t>(n)] != 0; }

  /// What was dropped since the last take_changes(): finalize closes again only the elements
  /// whose graph that changed (finalize_rechecks.hpp).
  struct Changes {
    std::vector<Index> segments;  // segments left out
    std::vector<Index> nodes;     // rim nodes left out
    bool whole_edges = false;     // whole S2 edges dropped (their intersection nodes go too)
  };
  Changes take_changes() { return std::exchange(changes_, Changes{}); }

 private:
  void report(Index e, Index t) {
    if (reported_[static_cast<std::size_t>(e)] || !report_) return;
    reported_[static_cast<std::size_t>(e)] = 1;
    report_->dropped_edges.push_back(e);
    report_->dropped_edge_element.push_back(t);
  }

  std::vector<char> dropped_;
  std::vector<char> reported_;
  std::vector<char> segment_dropped_;
  std::vector<char> node_dropped_;  // per builder node once a rim node is dropped, else empty
  bool rim_segments_dropped_ = false;
  Changes changes_;
  std::vector<char>& edge_inserted_;
  FinalizeReport* report_;
};

/// Whether S2 element t contains the image of a support (all its vertices are corners of t).
template <int d>
bool support_in_element(const Surface<d>& s2, const Support<d>& s, Index t) {
  if (t == s.element) return true;
  for (int i = 0; i < s.count; ++i)
    if (s2.local_corner(t, s.vertex(s2, i)) < 0) return false;
  return true;
}

[[noreturn, gnu::cold]] void throw_not_in_element(Index t, Index vertex);

/// Local coordinates of a support on an S2 element that contains it (exact transfer): the
/// weights of the element's corners 1 .. d, copied. Called for every node and region corner.
template <int d>
LocalPoint<d> support_local(const Surface<d>& s2, const Support<d>& s, Index t) {
  LocalPoint<d> y = LocalPoint<d>::Zero();
  if (t == s.element) {  // the corners are known
    for (int i = 0; i < s.count; ++i)
      if (const int k = s.corner(i); k > 0) y(k - 1) = s.weight[i];
    return y;
  }
  const auto& corners = s2.element(t);
  for (int i = 0; i < s.count; ++i) {
    const Index v = s.vertex(s2, i);
    if (v == corners[0]) continue;
    int k = 1;
    while (k <= d && corners[k] != v) ++k;
    if (k > d) throw_not_in_element(t, v);
    y(k - 1) = s.weight[i];
  }
  return y;
}

}  // namespace plmap::detail
