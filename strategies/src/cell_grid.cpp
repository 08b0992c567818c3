#include <plmap/core/errors.hpp>
#include <plmap/strategies/point_location/cell_grid.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace plmap::point_location {

namespace {

// chosen_side[mask][coin]: the side to cross when the sides in `mask` separate p (bit i: the side
// opposite corner i). Masks 0 and 7 cannot occur in a walk step on a positively oriented region.
constexpr std::array<std::array<std::int8_t, 2>, 8> chosen_side = {
    {{0, 0}, {0, 0}, {1, 1}, {0, 1}, {2, 2}, {0, 2}, {1, 2}, {0, 1}}};

// Widening of a cell before it is certified. A query p lands in cell (i, j) when the rounded
// products p.x G, p.y G fall in [i, i + 1) x [j, j + 1); with |p| <= 1 (other points never reach
// a certified answer) p is then within 2^-52 of the exact cell, and the rounded cell corners are
// within 2^-53 of theirs. 2^-40 covers both with a wide safety factor and is still negligible
// against a cell (at least 1/512 wide).
constexpr double certification_margin = 0x1p-40;

}  // namespace

bool CellGrid::contains(Index region, const LocalPoint<2>& p) const {
  const RegionRecord& r = records_[static_cast<std::size_t>(region)];
  return orient2d(r.corner[0], r.corner[1], p) >= 0 && orient2d(r.corner[1], r.corner[2], p) >= 0 &&
         orient2d(r.corner[2], r.corner[0], p) >= 0;
}

Index CellGrid::scan(const ElementGrid& e, const LocalPoint<2>& p) const {
  for (Index r = e.first_region; r < e.end_region; ++r)
    if (contains(r, p)) return r;
  return invalid_index;
}

Index CellGrid::walk(const ElementGrid& e, const LocalPoint<2>& p, Index region) const {
  // Non-finite coordinates are outside every region (and must not reach the exact predicate).
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return invalid_index;
  if (e.first_region == e.end_region) return invalid_index;
  // A walk never needs more steps than there are regions unless it wanders; a wandering walk is
  // cheaper to cut short than to let run.
  const Index budget = 4 * (e.end_region - e.first_region) + 16;
  for (Index step = 0; step < budget; ++step) {
    const RegionRecord& r = records_[static_cast<std::size_t>(region)];
    // All three tests before branching: one unpredictable branch per step instead of three.
    const unsigned separating = unsigned(orient2d(r.corner[1], r.corner[2], p) < 0) |
                                unsigned(orient2d(r.corner[2], r.corner[0], p) < 0) << 1 |
                                unsigned(orient2d(r.corner[0], r.corner[1], p) < 0) << 2;
    if (separating == 0) return region;
    // The coin: one bit of a multiplicative hash of (region, step). It varies along the walk as a
    // random coin does, but is fixed by the query, so the locator stays deterministic.
    const std::uint32_t hash =
        (static_cast<std::uint32_t>(region) ^ (static_cast<std::uint32_t>(step) * 0x9e3779b9u)) *
        0x85ebca6bu;
    const Index next = r.neighbor[static_cast<std::size_t>(chosen_side[separating][hash >> 31])];
    if (next == invalid_index) break;  // left D ∩ T here; p may still be in another part
    region = next;
  }
  return scan(e, p);
}

bool CellGrid::on_element_boundary(const LocalPoint<2>& a, const LocalPoint<2>& b) {
  static const LocalPoint<2> corner1(1, 0), corner2(0, 1);
  return (a.x() == 0 && b.x() == 0) || (a.y() == 0 && b.y() == 0) ||
         (orient2d(corner1, corner2, a) == 0 && orient2d(corner1, corner2, b) == 0);
}

bool CellGrid::holds_within_element(Index region, const std::array<LocalPoint<2>, 4>& box) const {
  const RegionRecord& r = records_[static_cast<std::size_t>(region)];
  for (int k = 0; k < 3; ++k) {
    const LocalPoint<2>& a = r.corner[static_cast<std::size_t>(next_corner[k])];
    const LocalPoint<2>& b = r.corner[static_cast<std::size_t>(next_corner[k + 1])];
    if (on_element_boundary(a, b)) continue;
    for (const LocalPoint<2>& c : box)
      if (orient2d(a, b, c) < 0) return false;
  }
  return true;
}

unsigned CellGrid::certify(Index region, const std::array<LocalPoint<2>, 4>& box) const {
  const auto inside = [&](Index r) {
    return std::all_of(box.begin(), box.end(), [&](const LocalPoint<2>& c) { return contains(r, c); });
  };
  // Regions are convex: the widened square is inside when its four corners are. A cell at the
  // element's boundary reaches outside the reference triangle, where no region is; but the
  // queries a certified cell answers lie inside it (locate() checks), so there the region only
  // has to hold the cell on the inner side of its sides that are not the triangle's own.
  if (inside(region) || holds_within_element(region, box)) return whole_cell;
  const RegionRecord& r = records_[static_cast<std::size_t>(region)];
  for (int k = 0; k < 3; ++k) {
    const Index other = r.neighbor[static_cast<std::size_t>(k)];
    if (other == invalid_index) continue;
    const LocalPoint<2>& apex = r.corner[static_cast<std::size_t>(k)];
    const LocalPoint<2>& s1 = r.corner[static_cast<std::size_t>(next_corner[k])];
    const LocalPoint<2>& s2 = r.corner[static_cast<std::size_t>(next_corner[k + 1])];
    // The neighbour must share the whole side (s2, s1); its third corner is the other apex.
    const RegionRecord& n = records_[static_cast<std::size_t>(other)];
    int shared = -1;
    for (int m = 0; m < 3; ++m)
      if (n.corner[static_cast<std::size_t>(m)] == s2 &&
          n.corner[static_cast<std::size_t>(next_corner[m])] == s1)
        shared = m;
    if (shared < 0) continue;
    const LocalPoint<2>& other_apex = n.corner[static_cast<std::size_t>(next_corner[shared + 1])];
    // The quadrilateral apex, s1, other_apex, s2 is the union of the two triangles; when it is
    // convex, it contains the square as soon as it contains the square's corners, and the line
    // s1 s2 cuts it into exactly the two triangles.
    const bool convex = orient2d(apex, s1, other_apex) >= 0 && orient2d(s1, other_apex, s2) >= 0 &&
                        orient2d(other_apex, s2, apex) >= 0;
    if (!convex) continue;
    if (std::all_of(box.begin(), box.end(), [&](const LocalPoint<2>& c) {
          return contains(region, c) || contains(other, c);
        }))
      return static_cast<unsigned>(k);
  }
  return start_cell;
}

Index CellGrid::most_covering(const ElementGrid& e, int i, int j, Index near) const {
  // The region found most often on a 3 x 3 sample of the cell (inside the reference triangle):
  // the walk from there most often ends after its first test.
  constexpr int samples = 3;
  std::array<std::pair<Index, int>, samples * samples> count{};
  std::size_t distinct = 0;
  Index from = near;
  for (int a = 0; a < samples; ++a)
    for (int b = 0; b < samples; ++b) {
      const LocalPoint<2> q((i + (a + 0.5) / samples) / e.side, (j + (b + 0.5) / samples) / e.side);
      if (q.x() + q.y() > 1) continue;
      const Index r = walk(e, q, from);
      if (r == invalid_index) continue;
      from = r;
      std::size_t k = 0;
      while (k < distinct && count[k].first != r) ++k;
      if (k == distinct) count[distinct++] = {r, 0};
      ++count[k].second;
    }
  if (distinct == 0) return near;
  return std::max_element(count.begin(), count.begin() + static_cast<std::ptrdiff_t>(distinct),
                          [](const auto& x, const auto& y) { return x.second < y.second; })
      ->first;
}

CellGrid::CellGrid(const PlMap<2>& map, const CellGridOptions& options)
    : map_(&map), regions_(map.region_count()) {
  if (!(options.cells_per_region > 0) || options.max_cells_per_side < 1 ||
      options.max_cells_per_side > 4096)
    throw Error("cell-grid locator: cells_per_region must be positive and max_cells_per_side in "
                "[1, 4096]");
  const MapData<2>& m = map.stored();
  const auto region_neighbors = map.region_neighbors();
  const Index element_count = map.domain().element_count();

  records_.resize(static_cast<std::size_t>(regions_));
  for (Index r = 0; r < regions_; ++r) {
    RegionRecord& record = records_[static_cast<std::size_t>(r)];
    for (int k = 0; k < 3; ++k) {
      record.corner[k] = m.node_position[m.region_corners[r][k]];
      record.neighbor[k] = region_neighbors[static_cast<std::size_t>(r)][k];
    }
  }

  images_ = region_images(map);

  elements_.resize(static_cast<std::size_t>(element_count));
  double whole_area = 0, split_area = 0;
  Index covered_elements = 0;
  for (Index t = 0; t < element_count; ++t) {
    ElementGrid& e = elements_[static_cast<std::size_t>(t)];
    e.first_region = m.region_begin[t];
    e.end_region = m.region_begin[t + 1];
    const Index n = e.end_region - e.first_region;
    // G (G + 1) / 2 cells should be about cells_per_region * n.
    int side = 1;
    if (n > 1) {
      const double wanted = options.cells_per_region * n;
      side = static_cast<int>(std::ceil((std::sqrt(1 + 8 * wanted) - 1) / 2));
      side = std::clamp(side, 1, options.max_cells_per_side);
    }
    e.side = side;
    e.scale = side;
    e.highest = side - 0.5;
    const std::size_t cell_count = static_cast<std::size_t>(side) * (side + 1) / 2;
    if (cells_.size() + cell_count > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
      throw Error("cell-grid locator: more than 2^31 cells at element " + std::to_string(t) +
                  "; lower cells_per_region");
    e.first_cell = static_cast<Index>(cells_.size());
    cells_.resize(cells_.size() + cell_count, static_cast<Cell>(start_cell));

    // Locate every cell's centre by walking from a nearby cell's region: along a row from the
    // previous cell, and each row from the first cell of the row before.
    Index row_start = m.start_region[t];
    double element_whole = 0, element_split = 0;
    for (int i = 0; i < side; ++i) {
      Index previous = row_start;
      for (int j = 0; j < side - i; ++j) {
        LocalPoint<2> centre((i + 0.5) / side, (j + 0.5) / side);
        // The centres of the diagonal cells lie on the slanted edge; pull them inside.
        if (i + j == side - 1) centre -= LocalPoint<2>(0.25 / side, 0.25 / side);
        const Index found = previous == invalid_index ? invalid_index : walk(e, centre, previous);
        // Centre outside D: start from a region nearby.
        Index region = previous == invalid_index ? e.first_region : previous;
        unsigned kind = start_cell;
        if (found != invalid_index) {
          previous = found;
          if (j == 0) row_start = found;
          const double x0 = double(i) / side - certification_margin;
          const double x1 = double(i + 1) / side + certification_margin;
          const double y0 = double(j) / side - certification_margin;
          const double y1 = double(j + 1) / side + certification_margin;
          const std::array<LocalPoint<2>, 4> box = {LocalPoint<2>(x0, y0), LocalPoint<2>(x1, y0),
                                                    LocalPoint<2>(x0, y1), LocalPoint<2>(x1, y1)};
          kind = found - e.first_region <= max_cell_offset ? certify(found, box) : start_cell;
          region = kind == start_cell ? most_covering(e, i, j, found) : found;
          const double area = (i + j == side - 1 ? 0.5 : 1.0) / (double(side) * side);
          if (kind == whole_cell) {
            ++memory_.whole_cells;
            element_whole += area;
          } else if (kind != start_cell) {
            ++memory_.split_cells;
            element_split += area;
          }
        }
        // A start region the 13-bit offset cannot name is replaced by the highest one it can:
        // any region of the element is a correct start.
        const Index offset = std::min(region - e.first_region, max_cell_offset);
        const Cell value = static_cast<Cell>(static_cast<unsigned>(offset) << kind_bits | kind);
        cells_[static_cast<std::size_t>(e.first_cell + row_offset(i, side) + j)] = value;
      }
    }
    if (n > 0) {
      ++covered_elements;
      whole_area += 2 * element_whole;  // the reference triangle has area 1/2
      split_area += 2 * element_split;
    }
  }
  cells_.shrink_to_fit();

  memory_.cells = cells_.size();
  memory_.whole_area = covered_elements > 0 ? whole_area / covered_elements : 0;
  memory_.split_area = covered_elements > 0 ? split_area / covered_elements : 0;
  memory_.region_record_bytes = records_.capacity() * sizeof(RegionRecord);
  memory_.region_image_bytes = images_.capacity() * sizeof(RegionImage<2>);
  memory_.cell_bytes = cells_.capacity() * sizeof(Cell);
  memory_.element_bytes = elements_.capacity() * sizeof(ElementGrid);
}

}  // namespace plmap::point_location
