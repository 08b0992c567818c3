#pragma once
/// \file
/// CellGridLocator: point location by a fine per-element grid of cells, most of which are
/// certified when the table is built, so that most queries are answered by one table look-up and
/// at most one orientation test, without a walk.
///
/// The reference triangle of every element is covered by the cells (i, j), i + j < G, of a
/// G x G grid on the unit square (G grows like the square root of the element's region count,
/// about `cells_per_region` cells per region, 2 bytes a cell). Each cell's closed square, widened
/// by a margin far larger than the rounding of the cell index computed from a query, is
/// classified with the exact orient2d on its corners (regions are convex):
/// - whole: it lies in one region, which is the answer for every query landing in the cell;
///   at the element's boundary, where the cell reaches outside the reference triangle, it lies
///   in one region as far as it lies in the triangle (the region's sides on the triangle's
///   edges are not tested), and a query is answered from it only if it lies in the triangle;
/// - split: it lies in the union of a region and its neighbour across one side, and that union
///   is convex, so the side's line divides the cell between the two: one orient2d answers;
/// - start: anything else; the query walks from the region covering most of the cell.
/// Every answer is a region containing the query exactly, as every other locator's is.
///
/// The walk reads the locator's own copy of the regions, one 64-byte record per region (its three
/// corners and three neighbours), so a step touches one cache line instead of chasing
/// region_corners -> node_position. The walk crosses a separating side chosen by a hash of the
/// region and the step number: as unpredictable as the Brown–Faigle coin (which is what breaks
/// cycles on non-Delaunay graphs), yet a function of the query alone, so answers do not depend
/// on earlier queries or on the thread count. Leaving D ∩ T or exceeding the step budget falls
/// back to scanning the element's records, with the same exact containment test as
/// detail::region_contains.
///
/// The locator also answers whole evaluations (EvaluatingPointLocator): it keeps every region's
/// RegionImage (its affine map, S2 element and that element's world frame; 128 bytes), so a query
/// whose cell is certified reads the cell and one two-line record, where evaluate_in_region would
/// go on through the map's region_target, region_map, S2's element corners and vertices. The
/// answers are bit for bit those of locate() + evaluate_in_region.
///
/// The table is derived from the map on first use (and rebuilt if the locator meets another map);
/// copies share it. Its memory is reported by CellGrid::memory() and is not part of the map's
/// compact form.

#include <plmap/core/evaluation.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/core/region_image.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace plmap::point_location {

/// Settings of the cell grid.
struct CellGridOptions {
  /// Cells per region of an element (the grid side follows); more cells certify a larger share
  /// of the element, at 2 bytes a cell.
  double cells_per_region = 32.0;
  /// Upper bound on the grid side G (the grid has G (G + 1) / 2 cells per element).
  int max_cells_per_side = 512;
};

/// What a cell grid holds, for reports.
struct CellGridMemory {
  std::size_t region_record_bytes = 0;  ///< 64 bytes per region
  std::size_t region_image_bytes = 0;   ///< 128 bytes per region (RegionImage)
  std::size_t cell_bytes = 0;           ///< 2 bytes per cell
  std::size_t element_bytes = 0;        ///< per-element grid headers
  std::size_t cells = 0;
  std::size_t whole_cells = 0;   ///< cells inside one region: answered without a geometric test
  std::size_t split_cells = 0;   ///< cells split by one region side: answered by one orient2d
  double whole_area = 0;         ///< share of the covered elements' area in whole cells
  double split_area = 0;         ///< share of the covered elements' area in split cells
  std::size_t total_bytes() const {
    return region_record_bytes + region_image_bytes + cell_bytes + element_bytes;
  }
};

/// The per-map tables of CellGridLocator.
class CellGrid {
 public:
  explicit CellGrid(const PlMap<2>& map, const CellGridOptions& options = {});

  bool built_for(const PlMap<2>& map) const {
    return map_ == &map && regions_ == map.region_count() &&
           static_cast<std::size_t>(map.domain().element_count()) == elements_.size();
  }

  /// The region of `element` containing p, or invalid_index when p is outside D.
  Index locate(Index element, const LocalPoint<2>& p) const {
    const ElementGrid& e = elements_[element];
    const double u = p.x() * e.scale, v = p.y() * e.scale;
    const int i = cell_coordinate(u, e.highest), j_in_square = cell_coordinate(v, e.highest);
    const int j = std::min(j_in_square, e.side - 1 - i);  // cells with i + j >= G are not stored
    const unsigned cell = cells_[static_cast<std::size_t>(e.first_cell + row_offset(i, e.side) + j)];
    const unsigned kind = cell & kind_mask;
    const Index region = e.first_region + static_cast<Index>(cell >> kind_bits);
    // Certified cells may answer only when p really maps to this cell: u and v were not clamped
    // (this also rejects NaN) and the cell is one of the stored ones. A cell whose widened square
    // crosses the slanted edge of the reference triangle (i + j >= G - 2) may be certified for
    // its part inside the triangle only, so there p must also lie on the inner side of that
    // edge (the other two are u >= 0, v >= 0).
    const bool in_cell = u >= 0 && v >= 0 && u < e.scale && v < e.scale && j == j_in_square &&
                         (i + j + 2 < e.side || left_of_or_on(slanted_edge_from, slanted_edge_to, p));
    if (kind <= whole_cell && in_cell) [[likely]] {
      if (kind == whole_cell) return region;
      // A split cell: p is in `region` on its side of the shared side's line, else in the
      // neighbour. One exact orientation test, no walk.
      const RegionRecord& r = records_[static_cast<std::size_t>(region)];
      return left_of_or_on(r.corner[next_corner[kind]], r.corner[next_corner[kind + 1]], p)
                 ? region
                 : r.neighbor[kind];
    }
    return walk(e, p, region);
  }

  /// Xi at (element, p): locate() and the region's record; exactly what evaluate_in_region on
  /// the map gives for that region.
  Evaluation<2> evaluate(Index element, const LocalPoint<2>& p) const {
    const Index region = locate(element, p);
    if (region == invalid_index) return {};
    return evaluate_in_region(images_[static_cast<std::size_t>(region)], region, p);
  }

  CellGridMemory memory() const { return memory_; }

 private:
  // A cell is 16 bits: the region's offset in its element (13 bits) and a kind (3 bits). Kinds
  // 0, 1, 2: the (widened) cell lies in the union of the region and its neighbour across that
  // side, which is convex, so the side's line splits the cell between the two; whole_cell: the
  // cell lies in the region; start_cell: nothing certified, walk from the region. Two bytes a
  // cell keep the table small enough to stay in cache next to the map.
  using Cell = std::uint16_t;
  static constexpr unsigned kind_bits = 3;
  static constexpr unsigned kind_mask = (1u << kind_bits) - 1;
  static constexpr unsigned whole_cell = 3;
  static constexpr unsigned start_cell = 4;
  /// Regions of an element beyond this offset are never named by a cell (their element's cells
  /// start walks from a lower one instead).
  static constexpr Index max_cell_offset = (1 << (16 - kind_bits)) - 1;
  static constexpr std::array<int, 4> next_corner = {1, 2, 0, 1};
  // The slanted edge of the reference triangle, from corner 1 to corner 2.
  static inline const LocalPoint<2> slanted_edge_from{1.0, 0.0}, slanted_edge_to{0.0, 1.0};

  struct alignas(64) RegionRecord {
    std::array<Eigen::Vector2d, 3> corner;
    std::array<Index, 3> neighbor;
  };
  static_assert(sizeof(RegionRecord) == 64);

  struct ElementGrid {
    double scale = 1;      ///< G as a double
    double highest = 0.5;  ///< G - 0.5: cell coordinates are clamped below it
    int side = 1;      ///< G
    Index first_cell = 0;
    Index first_region = 0;
    Index end_region = 0;
  };

  /// orient2d(a, b, p) >= 0, exactly, with orient2d's filter inlined: the two tests of the query
  /// path (split cells, the slanted edge) are nearly always decided by it, and the call to
  /// orient2d cost more than the test.
  static bool left_of_or_on(const LocalPoint<2>& a, const LocalPoint<2>& b, const LocalPoint<2>& p) {
    const int sign = orient2d_by_filter(a, b, p);
    return sign != 0 ? sign > 0 : orient2d(a, b, p) >= 0;
  }

  // Clamped to [0, G - 1]; std::max(0.0, NaN) is 0, so NaN lands in cell 0 (and is not in_cell).
  static int cell_coordinate(double u, double highest) {
    return static_cast<int>(std::min(std::max(0.0, u), highest));
  }
  // i >= 0, so i (i - 1) >= 0 and halving it unsigned is the same, without a sign fix-up.
  static Index row_offset(int i, int side) {
    return i * side - static_cast<Index>(static_cast<unsigned>(i * (i - 1)) / 2);
  }

  /// Randomized-by-hash walk from `region`; scans the element when it leaves D or wanders.
  Index walk(const ElementGrid& e, const LocalPoint<2>& p, Index region) const;
  Index scan(const ElementGrid& e, const LocalPoint<2>& p) const;
  bool contains(Index region, const LocalPoint<2>& p) const;
  /// How the widened cell with corners `box` relates to `region`, which contains its centre:
  /// whole_cell, a side k splitting it between region and that neighbour, or start_cell.
  unsigned certify(Index region, const std::array<LocalPoint<2>, 4>& box) const;
  /// Whether the widened cell `box` lies on the inner side of each side of `region` that is not
  /// on the reference triangle's boundary: then the region holds every point of the cell that
  /// lies in the triangle.
  bool holds_within_element(Index region, const std::array<LocalPoint<2>, 4>& box) const;
  /// Whether the segment a b lies on an edge of the reference triangle (x = 0, y = 0 or
  /// x + y = 1, exactly).
  static bool on_element_boundary(const LocalPoint<2>& a, const LocalPoint<2>& b);
  /// The start region for an uncertified cell (i, j): the one covering most of it.
  Index most_covering(const ElementGrid& e, int i, int j, Index near) const;

  const PlMap<2>* map_ = nullptr;
  Index regions_ = 0;
  std::vector<ElementGrid> elements_;
  std::vector<Cell> cells_;
  std::vector<RegionRecord> records_;
  std::vector<RegionImage<2>> images_;
  CellGridMemory memory_;
};

class CellGridLocator {
 public:
  explicit CellGridLocator(const CellGridOptions& options = {}) : options_(options) {}

  RegionLocation<2> locate(const PlMap<2>& map, Index element, const LocalPoint<2>& p) {
    prepare(map);
    return {grid_->locate(element, p)};
  }

  /// Xi(p) through the table's region records (see the file comment): what evaluate() calls.
  Evaluation<2> evaluate(const PlMap<2>& map, const SurfacePoint<2>& p) {
    prepare(map);
    return grid_->evaluate(p.element, p.local);
  }
  /// The same on the map of the last prepare(), unchecked (PreparedEvaluatingPointLocator).
  Evaluation<2> evaluate_prepared(const SurfacePoint<2>& p) const {
    return grid_->evaluate(p.element, p.local);
  }

  /// Builds the tables now (evaluate_batch copies the locator per thread; preparing it first
  /// lets the copies share one table and keeps the build out of the query loop).
  void prepare(const PlMap<2>& map) {
    if (!grid_ || !grid_->built_for(map)) grid_ = std::make_shared<const CellGrid>(map, options_);
  }

  /// The tables, once prepared (null before).
  const CellGrid* grid() const { return grid_.get(); }

  /// Bytes of the tables (0 before prepare); not part of the map's compact form.
  std::size_t memory_bytes() const { return grid_ ? grid_->memory().total_bytes() : 0; }

 private:
  CellGridOptions options_;
  std::shared_ptr<const CellGrid> grid_;
};

static_assert(PreparedEvaluatingPointLocator<CellGridLocator, 2>);

}  // namespace plmap::point_location
