#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace plmap {

namespace {

/// Region corner k of an index entry's corner j (the entry may list the corners reversed).
template <int d>
int region_corner_of(bool reversed, int j) {
  if (!reversed) return j;
  if constexpr (d == 1)
    return 1 - j;
  else
    return j == 0 ? 0 : 3 - j;  // (0, 1, 2) -> (0, 2, 1)
}

/// Weights of y on the entry's image, unnormalised: for d = 2 twice the signed areas of the
/// sub-triangles opposite each corner (all >= 0 iff y is in the closed image), for d = 1 the
/// lengths of the two sub-intervals.
inline std::array<double, 3> raw_weights(const InverseIndex<2>::Entry& e, const LocalPoint<2>& y) {
  const auto& c = e.image_corners;
  auto cross = [](const LocalPoint<2>& a, const LocalPoint<2>& b, const LocalPoint<2>& p) {
    return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
  };
  return {cross(c[1], c[2], y), cross(c[2], c[0], y), cross(c[0], c[1], y)};
}
inline std::array<double, 2> raw_weights(const InverseIndex<1>::Entry& e, const LocalPoint<1>& y) {
  return {e.image_corners[1](0) - y(0), y(0) - e.image_corners[0](0)};
}

/// How far inside the entry's image y lies, in local units of the S2 element: the smallest
/// signed distance to a side (negative outside).
template <int d>
double inside_margin(const typename InverseIndex<d>::Entry& e, const std::array<double, d + 1>& w) {
  double margin = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= d; ++i) {
    double side = 1.0;  // d = 1: the weights are lengths already
    if constexpr (d == 2) side = (e.image_corners[(i + 2) % 3] - e.image_corners[(i + 1) % 3]).norm();
    margin = std::min(margin, w[i] / side);
  }
  return margin;
}

/// The first entry whose closed image contains y (as computed in doubles), or nullptr.
template <int d>
const typename InverseIndex<d>::Entry* find_containing(std::span<const typename InverseIndex<d>::Entry> entries,
                                                       const LocalPoint<d>& y, std::array<double, d + 1>& w) {
  for (const auto& e : entries) {
    w = raw_weights(e, y);
    bool inside = true;
    for (int i = 0; i <= d; ++i) inside &= w[i] >= 0.0;
    if (inside) return &e;
  }
  return nullptr;
}

/// Whether y is in the entry's closed image (as computed in doubles); its weights in `w`.
template <int d>
bool contains(const typename InverseIndex<d>::Entry& e, const LocalPoint<d>& y, std::array<double, d + 1>& w) {
  w = raw_weights(e, y);
  bool inside = true;
  for (int k = 0; k <= d; ++k) inside &= w[k] >= 0.0;
  return inside;
}

/// find_containing over the element's entries, or over its grid cell's if it has a grid.
template <int d>
const typename InverseIndex<d>::Entry* find_in_element(const InverseIndex<d>& index, Index element,
                                                       const LocalPoint<d>& y, std::array<double, d + 1>& w) {
  const auto entries = index.entries(element);
  if (!index.has_grid(element)) return find_containing<d>(entries, y, w);
  const auto& cell = index.cell(element, y);
  // The cell names its candidates: ask for all of their entries now, so that the memory
  // latencies overlap where the first candidate is not the answer.
  for (int k = 1; k < InverseIndex<d>::inline_candidates && cell.candidate[k] != invalid_index; ++k)
    __builtin_prefetch(&entries[static_cast<std::size_t>(cell.candidate[k])], 0, 3);
  for (const Index i : cell.candidate) {
    if (i == invalid_index) return nullptr;
    if (contains<d>(entries[static_cast<std::size_t>(i)], y, w)) return &entries[static_cast<std::size_t>(i)];
  }
  for (const Index i : index.overflow(cell))
    if (contains<d>(entries[static_cast<std::size_t>(i)], y, w)) return &entries[static_cast<std::size_t>(i)];
  return nullptr;
}

/// Calls f(entry) for every entry of `element` whose image may come within the tolerance of y:
/// its grid cell's candidates, or all of the element's entries if it has no grid.
template <int d, class F>
void for_each_nearby_entry(const InverseIndex<d>& index, Index element, const LocalPoint<d>& y, F&& f) {
  const auto entries = index.entries(element);
  if (!index.has_grid(element)) {
    for (const auto& e : entries) f(e);
    return;
  }
  const auto& cell = index.cell(element, y);
  for (const Index i : cell.candidate)
    if (i != invalid_index) f(entries[static_cast<std::size_t>(i)]);
  for (const Index i : index.overflow(cell)) f(entries[static_cast<std::size_t>(i)]);
}

template <int d>
InverseEvaluation<d> preimage_from_weights(const typename InverseIndex<d>::Entry& e, std::array<double, d + 1> w) {
  double sum = 0.0;
  for (auto& x : w) sum += x = std::max(x, 0.0);  // clamps weights of points just outside
  InverseEvaluation<d> out;
  if (!(sum > 0.0)) return out;  // a degenerate image: no answer from it
  out.in_image = true;
  out.region = e.region;
  out.preimage.element = e.element;
  LocalPoint<d> xi = LocalPoint<d>::Zero();
  WorldPoint<d> world = WorldPoint<d>::Zero();
  for (int j = 0; j <= d; ++j) {
    xi += (w[j] / sum) * e.preimage_local[j];
    world += (w[j] / sum) * e.preimage_world[j];
  }
  out.preimage.local = xi;
  out.world = world;
  return out;
}

/// A key that orders points of the reference element along a Z-order curve: images close on
/// the element get close positions in its entry list, so the candidates of one grid cell share
/// cache lines.
template <int d>
std::uint64_t z_order_key(const LocalPoint<d>& p) {
  constexpr double scale = 65535.0;
  auto quantise = [](double x) -> std::uint64_t {
    const double c = std::clamp(x, 0.0, 1.0) * scale;
    return c >= 0.0 ? static_cast<std::uint64_t>(c) : 0;  // NaN -> 0
  };
  if constexpr (d == 1) {
    return quantise(p(0));
  } else {
    std::uint64_t x = quantise(p(0)), y = quantise(p(1)), key = 0;
    for (int bit = 0; bit < 16; ++bit) key |= ((x >> bit) & 1u) << (2 * bit) | ((y >> bit) & 1u) << (2 * bit + 1);
    return key;
  }
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
InverseIndex<d>::InverseIndex(const PlMap<d>& map, InverseOptions options) : map_(&map), options_(options) {
  if (!(options_.tolerance >= 0.0 && options_.tolerance < 1.0 / (d + 1)))
    throw Error("inverse evaluation: tolerance must lie in [0, 1/" + std::to_string(d + 1) + "), not " +
                std::to_string(options_.tolerance));
  const MapData<d>& m = map.stored();
  const Index targets = map.target().element_count();
  begin_.assign(static_cast<std::size_t>(targets) + 1, 0);
  for (Index t : m.region_target) ++begin_[static_cast<std::size_t>(t) + 1];
  for (Index e = 0; e < targets; ++e) begin_[e + 1] += begin_[e];
  entry_.resize(m.region_target.size());
  std::vector<Index> fill(begin_.begin(), begin_.end() - 1);
  const Index elements = map.domain().element_count();
  for (Index t = 0; t < elements; ++t)
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
      Entry& e = entry_[fill[m.region_target[r]]++];
      e.region = r;
      e.element = t;
      for (int k = 0; k <= d; ++k) e.image_corners[k] = apply<d>(m.region_map[r], m.node_position[m.region_corners[r][k]]);
      // Maps that reverse orientation have clockwise (decreasing) images: list them reversed.
      if constexpr (d == 1) {
        e.reversed = e.image_corners[1](0) < e.image_corners[0](0);
        if (e.reversed) std::swap(e.image_corners[0], e.image_corners[1]);
      } else {
        const auto& c = e.image_corners;
        const double area2 = (c[1] - c[0]).x() * (c[2] - c[0]).y() - (c[1] - c[0]).y() * (c[2] - c[0]).x();
        e.reversed = area2 < 0.0;
        if (e.reversed) std::swap(e.image_corners[1], e.image_corners[2]);
      }
    }
  for (Entry& e : entry_)
    for (int j = 0; j <= d; ++j) {
      e.preimage_local[j] = m.node_position[m.region_corners[e.region][region_corner_of<d>(e.reversed, j)]];
      e.preimage_world[j] = map.domain().world_position(e.element, e.preimage_local[j]);
    }
  sort_entries_spatially();
  build_grids();
}

template <int d>
  requires SurfaceDimension<d>
std::size_t InverseIndex<d>::memory_bytes() const {
  return (begin_.capacity() + grid_of_.capacity() + cell_overflow_.capacity()) * sizeof(Index) + cells_.capacity() * sizeof(Cell) +
         entry_.capacity() * sizeof(Entry) +
         grids_.capacity() * sizeof(Grid);
}

template <int d>
  requires SurfaceDimension<d>
void InverseIndex<d>::sort_entries_spatially() {
  const Index targets = static_cast<Index>(begin_.size()) - 1;
  std::vector<std::pair<std::uint64_t, Entry>> keyed;
  for (Index t = 0; t < targets; ++t) {
    if (begin_[t + 1] - begin_[t] <= grid_threshold) continue;  // scanned whole: order is irrelevant
    const auto first = entry_.begin() + begin_[t], last = entry_.begin() + begin_[t + 1];
    keyed.clear();
    for (auto it = first; it != last; ++it) {
      LocalPoint<d> centroid = LocalPoint<d>::Zero();
      for (const auto& c : it->image_corners) centroid += c / double(d + 1);
      keyed.emplace_back(z_order_key<d>(centroid), *it);
    }
    // stable, with the region as the tie-break, so that the order does not depend on the sort
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first < b.first : a.second.region < b.second.region;
    });
    std::transform(keyed.begin(), keyed.end(), first, [](const auto& k) { return k.second; });
  }
}

namespace {

/// The grid cell (per axis) of a local coordinate, clamped into the grid. Monotone in x, so a
/// point inside a bounding box falls into a cell the box was registered in.
inline Index grid_cell(double x, Index side) {
  const double c = std::floor(x * side);
  if (!(c >= 0)) return 0;  // also NaN, which then matches no image
  return c >= side ? side - 1 : static_cast<Index>(c);
}

/// How many of a few sample points of grid cell `cell` (row-major, `side` cells per side) lie in
/// the entry's closed image: the centre and four points halfway to the corners (d = 1: three
/// points). Only orders the candidates; which image answers a query does not depend on it.
template <class Entry, int d = static_cast<int>(std::tuple_size_v<decltype(Entry::image_corners)>) - 1>
int cell_coverage(const Entry& e, Index cell, Index side) {
  const double h = 1.0 / double(side);
  int count = 0;
  auto inside = [&](const LocalPoint<d>& p) {
    const auto w = raw_weights(e, p);
    bool in = true;
    for (double x : w) in &= x >= 0.0;
    count += in;
  };
  if constexpr (d == 1) {
    for (double f : {0.25, 0.5, 0.75}) inside(LocalPoint<1>((double(cell) + f) * h));
  } else {
    const double x0 = double(cell % side) * h, y0 = double(cell / side) * h;
    for (const auto& [fx, fy] : {std::pair{0.5, 0.5}, {0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}})
      inside(LocalPoint<2>(x0 + fx * h, y0 + fy * h));
  }
  return count;
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
Index InverseIndex<d>::cell_index(Index target_element, const LocalPoint<d>& local) const {
  const Grid& g = grids_[grid_of_[target_element]];
  Index cell = grid_cell(local(0), g.side);
  if constexpr (d == 2) cell += g.side * grid_cell(local(1), g.side);
  return g.first_cell + cell;
}

template <int d>
  requires SurfaceDimension<d>
std::vector<Index> InverseIndex<d>::cell_candidates(Index target_element, const LocalPoint<d>& local) const {
  const Cell& c = cell(target_element, local);
  std::vector<Index> out;
  for (const Index i : c.candidate)
    if (i != invalid_index) out.push_back(i);
  const auto rest = overflow(c);
  out.insert(out.end(), rest.begin(), rest.end());
  return out;
}

template <int d>
  requires SurfaceDimension<d>
void InverseIndex<d>::build_grids() {
  const Index targets = static_cast<Index>(begin_.size()) - 1;
  grid_of_.assign(static_cast<std::size_t>(targets), invalid_index);
  cells_.clear();
  cell_overflow_.clear();
  // An image is listed in every cell that it meets when the cell is grown by the tolerance (and
  // a little more for the rounding of this test): every image that contains a point of the cell,
  // or comes within the tolerance of one, is then among the cell's candidates.
  const double slack = options_.tolerance + 64 * std::numeric_limits<double>::epsilon();
  for (Index e = 0; e < targets; ++e) {
    const auto list = entries(e);
    const Index count = static_cast<Index>(list.size());
    if (count <= grid_threshold) continue;
    // about four cells per image on the reference element (half of a square grid for d = 2):
    // then the image that covers most of a cell usually contains the whole cell, and most
    // queries are answered by the cell's first candidate alone
    const Index side = d == 1 ? 4 * count : std::max<Index>(2, static_cast<Index>(std::ceil(std::sqrt(8.0 * count))));
    const Index cells = d == 1 ? side : side * side;
    const double h = 1.0 / double(side);
    grid_of_[e] = static_cast<Index>(grids_.size());
    grids_.push_back({side, static_cast<Index>(cells_.size())});
    std::vector<std::vector<Index>> cell_lists(static_cast<std::size_t>(cells));
    for (Index i = 0; i < count; ++i) {
      const auto& corners = list[i].image_corners;
      LocalPoint<d> lo = corners[0], hi = lo;
      for (int k = 1; k <= d; ++k) lo = lo.cwiseMin(corners[k]), hi = hi.cwiseMax(corners[k]);
      lo.array() -= slack;
      hi.array() += slack;
      const Index x0 = grid_cell(lo(0), side), x1 = grid_cell(hi(0), side);
      Index y0 = 0, y1 = 0;
      if constexpr (d == 2) y0 = grid_cell(lo(1), side), y1 = grid_cell(hi(1), side);
      for (Index y = y0; y <= y1; ++y)
        for (Index x = x0; x <= x1; ++x) {
          if constexpr (d == 2) {
            // Separating axes beyond the bounding box's: a side of the image (positively
            // oriented, inside on the left) with the whole grown cell strictly outside it.
            bool separated = false;
            for (int k = 0; k < 3 && !separated; ++k) {
              const LocalPoint<2> a = corners[k], b = corners[(k + 1) % 3];
              const LocalPoint<2> outward(b.y() - a.y(), a.x() - b.x());
              const double reach = slack * outward.norm();
              double nearest = std::numeric_limits<double>::infinity();
              for (const double cx : {double(x) * h - slack, double(x + 1) * h + slack})
                for (const double cy : {double(y) * h - slack, double(y + 1) * h + slack})
                  nearest = std::min(nearest, outward.dot(LocalPoint<2>(cx, cy) - a));
              separated = nearest > reach;
            }
            if (separated) continue;
          }
          cell_lists[static_cast<std::size_t>(y * side + x)].push_back(i);
        }
    }
    for (std::size_t k = 0; k < cell_lists.size(); ++k) {
      auto& c = cell_lists[k];
      // Most queries stop at the first image that contains them: list the images that cover
      // most of the cell first (counted at a few sample points), so that they are tested first.
      if (c.size() > 1) {
        std::vector<std::pair<int, Index>> ranked;
        for (Index i : c) ranked.emplace_back(-cell_coverage(list[i], static_cast<Index>(k), side), i);
        std::sort(ranked.begin(), ranked.end());
        for (std::size_t j = 0; j < c.size(); ++j) c[j] = ranked[j].second;
      }
      Cell cell;
      cell.overflow_begin = static_cast<Index>(cell_overflow_.size());
      for (std::size_t j = 0; j < c.size(); ++j) {
        if (j < static_cast<std::size_t>(inline_candidates))
          cell.candidate[j] = c[j];
        else
          cell_overflow_.push_back(c[j]);
      }
      cells_.push_back(cell);
    }
  }
  Cell end;  // ends the last overflow list
  end.overflow_begin = static_cast<Index>(cell_overflow_.size());
  cells_.push_back(end);
}

template <int d>
InverseEvaluation<d> inverse_evaluate(const InverseIndex<d>& index, const SurfacePoint<d>& y) {
  const Surface<d>& s2 = index.map().target();
  if (y.element < 0 || y.element >= s2.element_count())
    throw Error("inverse evaluation: point on S2 element " + std::to_string(y.element) + ", but S2 has " +
                std::to_string(s2.element_count()) + " elements");
  using Entry = typename InverseIndex<d>::Entry;
  std::array<double, d + 1> w;
  // The common case: an image in y's own element contains y.
  if (const Entry* e = find_in_element(index, y.element, y.local, w)) return preimage_from_weights<d>(*e, w);
  // On an edge or vertex of S2: the images in the other incident elements.
  const double tolerance = index.options().tolerance;
  struct Candidate {
    Index element;
    LocalPoint<d> local;
  };
  std::vector<Candidate> candidates{{y.element, y.local}};
  for (Index other : elements_sharing_boundary_point(s2, y, tolerance)) {
    const auto local = transfer_to_element(s2, y, other, tolerance);
    if (!local) continue;
    if (const Entry* e = find_in_element(index, other, *local, w)) return preimage_from_weights<d>(*e, w);
    candidates.push_back({other, *local});
  }
  // Rounding gaps between images: the image with the largest margin, if within the tolerance.
  const Entry* best = nullptr;
  std::array<double, d + 1> best_w{};
  double best_margin = -tolerance;
  for (const Candidate& c : candidates)
    for_each_nearby_entry<d>(index, c.element, c.local, [&](const Entry& e) {
      const auto cw = raw_weights(e, c.local);
      // A weight below -2 tolerance puts y farther than the tolerance from that side (sides of
      // images in the reference element are shorter than 2): skip the side lengths' roots.
      for (double x : cw)
        if (x < -2.0 * tolerance) return;
      const double margin = inside_margin<d>(e, cw);
      if (margin >= best_margin) best = &e, best_w = cw, best_margin = margin;
    });
  if (best == nullptr) return {};
  return preimage_from_weights<d>(*best, best_w);
}

template <int d>
void inverse_evaluate_batch(const InverseIndex<d>& index, std::span<const SurfacePoint<d>> points,
                            std::span<InverseEvaluation<d>> out, unsigned threads) {
  if (out.size() != points.size())
    throw Error("inverse_evaluate_batch: output span size differs from the number of points");
  const Index elements = index.map().target().element_count();
  for (const auto& p : points)
    if (p.element < 0 || p.element >= elements)
      throw Error("inverse_evaluate_batch: query point on S2 element " + std::to_string(p.element) +
                  ", but S2 has " + std::to_string(elements) + " elements");
  parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) out[i] = inverse_evaluate(index, points[i]);
  });
}

template class InverseIndex<1>;
template class InverseIndex<2>;
template InverseEvaluation<1> inverse_evaluate(const InverseIndex<1>&, const SurfacePoint<1>&);
template InverseEvaluation<2> inverse_evaluate(const InverseIndex<2>&, const SurfacePoint<2>&);
template void inverse_evaluate_batch(const InverseIndex<1>&, std::span<const SurfacePoint<1>>,
                                     std::span<InverseEvaluation<1>>, unsigned);
template void inverse_evaluate_batch(const InverseIndex<2>&, std::span<const SurfacePoint<2>>,
                                     std::span<InverseEvaluation<2>>, unsigned);

}  // namespace plmap
