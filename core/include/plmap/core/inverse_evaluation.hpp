#pragma once
/// \file
/// Inverse evaluation Xi^{-1}: Xi(D) ⊂ S2 -> D ⊂ S1 (paper section 2.3 read backwards).
///
/// The compact form is indexed by S1 element; the inverse needs the opposite direction. An
/// InverseIndex, built on demand from a PlMap, lists for every S2 element the regions whose image
/// lies in it (CSR arrays), each with the corners of its image triangle (interval for d = 1) in
/// the S2 element's local coordinates. A query (S2 element, local coordinates) looks for the image
/// that contains the point among the regions of its element (where an element has many, among
/// those listed in the point's cell of a grid over the element), takes the point's barycentric weights in
/// that image and applies them to the region's corners on S1: the preimage lies in the region by
/// construction.
///
/// Points on an S2 edge or vertex are found from any element incident to it: when no image in the
/// given element contains the point and the point lies on the element's boundary (to within the
/// tolerance), the elements sharing that edge or vertex are searched too, with the point's
/// barycentric weights moved by vertex identity (element_transfer.hpp).
///
/// Images of neighbouring regions are computed from different affine maps, so they meet only up to
/// rounding. A point in no image exactly but within `tolerance` (in the S2 element's local
/// coordinates, hence relative to its size) of one is attributed to the nearest such image, its
/// barycentric weights clamped onto it; farther points are outside Xi(D) and reported as such.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/pl_map.hpp>

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace plmap {

/// Settings of inverse evaluation.
struct InverseOptions {
  /// Points this close to an image (in local coordinates of their S2 element, i.e. relative to
  /// its size) count as in it: the gaps and overlaps that rounding leaves between the images of
  /// neighbouring regions are a few 1e-16 wide.
  double tolerance = 1e-10;
};

/// Xi^{-1} at one point of S2.
template <int d>
struct InverseEvaluation {
  bool in_image = false;          ///< false: the point is outside Xi(D), the rest is unset
  Index region = invalid_index;   ///< the region of the map whose image contains the point
  SurfacePoint<d> preimage;       ///< S1 element and local coordinates of Xi^{-1}(y)
  WorldPoint<d> world = WorldPoint<d>::Zero();  ///< Xi^{-1}(y) in world coordinates on S1
};

/// For every S2 element, the regions of a map whose image lies in it (see the file comment).
/// Holds a reference to the map's shared state: the map must outlive the index.
template <int d>
  requires SurfaceDimension<d>
class InverseIndex {
 public:
  /// One region whose image lies in the element, with the image's corners in local coordinates
  /// of the S2 element, ordered so that the image is positively oriented (d = 2) or increasing
  /// (d = 1); `reversed` says that this order is the region's corner order reversed.
  ///
  /// An entry also holds its region's corners on S1, so that a query reads neither the map's
  /// region and node arrays nor S1's elements and vertices: those are large and read at random
  /// where S2 is much coarser than S1. The image corners fill the entry's first cache line (the
  /// containment test of a candidate reads only that line), the S1 corners the next two.
  struct alignas(64) Entry {
    std::array<LocalPoint<d>, d + 1> image_corners;
    Index region = invalid_index;
    Index element = invalid_index;  ///< the S1 element of the region
    bool reversed = false;
    /// The region's corners in the local coordinates of `element`, in image_corners' order
    /// (the reversal applied), and the same corners in space.
    std::array<LocalPoint<d>, d + 1> preimage_local;
    std::array<WorldPoint<d>, d + 1> preimage_world;
  };

  explicit InverseIndex(const PlMap<d>& map, InverseOptions options = {});

  const PlMap<d>& map() const { return *map_; }
  const InverseOptions& options() const { return options_; }

  /// The regions whose image lies in S2 element `target_element`.
  std::span<const Entry> entries(Index target_element) const {
    return {entry_.data() + begin_[target_element], entry_.data() + begin_[target_element + 1]};
  }

  /// Elements with more than this many regions get a grid of cells (below).
  static constexpr Index grid_threshold = 32;

  /// Whether `target_element` has more than grid_threshold regions and hence a grid of cells.
  bool has_grid(Index target_element) const { return grid_of_[target_element] != invalid_index; }

  /// A cell of an element's grid: the entries (positions in entries(target_element)) whose image
  /// comes within the tolerance of the cell. The first `inline_candidates` are stored in the cell
  /// itself, the image that covers most of the cell first, so that a query reads the cell and
  /// then asks for all of its candidates' entries at once instead of one after the other; the
  /// rare rest is in an overflow list.
  static constexpr int inline_candidates = 3;
  struct Cell {
    std::array<Index, inline_candidates> candidate{invalid_index, invalid_index, invalid_index};
    Index overflow_begin = 0;  ///< into the overflow list; it ends at the next cell's overflow_begin
  };

  /// For an element with a grid: the cell that contains the point with local coordinates `local`
  /// (points outside the reference element: the nearest cell).
  const Cell& cell(Index target_element, const LocalPoint<d>& local) const {
    return cells_[static_cast<std::size_t>(cell_index(target_element, local))];
  }
  /// The candidates of a cell beyond its inline ones.
  std::span<const Index> overflow(const Cell& c) const {
    return {cell_overflow_.data() + c.overflow_begin, cell_overflow_.data() + (&c + 1)->overflow_begin};
  }

  /// For an element with a grid: every entry (position in entries(target_element)) whose image
  /// may contain, or come within the tolerance of, the point with local coordinates `local`:
  /// the candidates of its cell. Where S2 is much coarser than S1 this keeps a query from
  /// scanning all of an element's images.
  std::vector<Index> cell_candidates(Index target_element, const LocalPoint<d>& local) const;

  /// The first of cell_candidates(target_element, local), the image that covers most of the
  /// cell, or invalid_index if the cell lists none.
  Index first_candidate(Index target_element, const LocalPoint<d>& local) const {
    return cell(target_element, local).candidate[0];
  }

  /// Bytes held by the index's arrays.
  std::size_t memory_bytes() const;

 private:
  const PlMap<d>* map_;
  InverseOptions options_;
  std::vector<Index> begin_;  ///< size |T2| + 1
  // The two arrays a query reads at random: on huge pages where the system offers them.
  std::vector<Entry, HugePageAllocator<Entry>> entry_;
  // Grids of the elements with more than grid_threshold regions: grid_of_[e] indexes grids_ or
  // is invalid; a grid's cells are cells_[first_cell ...], listing positions in entries(e).
  struct Grid {
    Index side = 0;        ///< cells per side (d = 1: cells)
    Index first_cell = 0;  ///< into cells_
  };
  Index cell_index(Index target_element, const LocalPoint<d>& local) const;
  void sort_entries_spatially();
  void build_grids();
  std::vector<Index> grid_of_;
  std::vector<Grid> grids_;
  std::vector<Cell, HugePageAllocator<Cell>> cells_;  ///< one more than there are cells: the last one ends the overflow
  std::vector<Index> cell_overflow_;
};

extern template class InverseIndex<1>;
extern template class InverseIndex<2>;

/// Xi^{-1}(y) for a point y = (S2 element, local coordinates). Throws plmap::Error if the
/// element is not one of S2's.
template <int d>
InverseEvaluation<d> inverse_evaluate(const InverseIndex<d>& index, const SurfacePoint<d>& y);

/// Xi^{-1} at many points on `threads` threads (0: all hardware threads), in contiguous ranges
/// (parallel_ranges.hpp). The result does not depend on the thread count. Throws plmap::Error,
/// before any work, if the sizes differ or a point names an element S2 does not have.
template <int d>
void inverse_evaluate_batch(const InverseIndex<d>& index, std::span<const SurfacePoint<d>> points,
                            std::span<InverseEvaluation<d>> out, unsigned threads = 0);

extern template InverseEvaluation<1> inverse_evaluate(const InverseIndex<1>&, const SurfacePoint<1>&);
extern template InverseEvaluation<2> inverse_evaluate(const InverseIndex<2>&, const SurfacePoint<2>&);
extern template void inverse_evaluate_batch(const InverseIndex<1>&, std::span<const SurfacePoint<1>>,
                                            std::span<InverseEvaluation<1>>, unsigned);
extern template void inverse_evaluate_batch(const InverseIndex<2>&, std::span<const SurfacePoint<2>>,
                                            std::span<InverseEvaluation<2>>, unsigned);

}  // namespace plmap
