#pragma once
/// \file
/// BrownFaigleWalk: randomized walk through the triangular regions of one element (Brown and
/// Faigle 1997; the "stochastic walk" of Devillers, Pion and Teillaud, "Walking in a
/// triangulation", 2002).
///
/// From the element's start region, the walk tests the three sides of the current triangle and
/// crosses a side whose supporting line separates the query point from the triangle, chosen at
/// random when two do; it stops in the triangle where no side does. The randomization is what
/// makes the walk terminate on any triangulation (a deterministic visibility walk can cycle on
/// non-Delaunay ones); its expected length is O(sqrt(n)) for n regions on "reasonable" inputs,
/// which is the bound the PSurface paper quotes.
///
/// Correctness never depends on the walk: every "inside" answer is an exact orient2d decision,
/// and whenever the walk meets a side with no neighbour (the element boundary, or the boundary of
/// D where D ∩ T is not convex) or exceeds its step budget, the element is scanned exhaustively.

#include <plmap/core/evaluation.hpp>
#include <plmap/strategies/point_location/region_geometry.hpp>

#include <array>
#include <cstdint>

namespace plmap::point_location {

class BrownFaigleWalk {
 public:
  static constexpr std::uint64_t default_seed = 0x5eed'b20f'a161'e997ULL;

  explicit BrownFaigleWalk(std::uint64_t seed = default_seed) : state_(mix(seed)) {}

  RegionLocation<2> locate(const PlMap<2>& map, Index element, const LocalPoint<2>& p) {
    return walk_from(map, element, p, map.stored().start_region[element]);
  }

  /// The walk from a given region of `element` (used by walks that choose their own start).
  RegionLocation<2> walk_from(const PlMap<2>& map, Index element, const LocalPoint<2>& p,
                              Index region) {
    const MapData<2>& m = map.stored();
    if (region == invalid_index) return {};
    const auto neighbors = map.region_neighbors();
    // Generous budget: a walk never needs more steps than there are regions unless it wanders,
    // and a wandering walk is cheaper to cut short than to let run.
    const Index budget = 4 * (m.region_begin[element + 1] - m.region_begin[element]) + 16;
    for (Index step = 0; step < budget; ++step) {
      const auto& corners = m.region_corners[region];
      const Eigen::Vector2d& a = m.node_position[corners[0]];
      const Eigen::Vector2d& b = m.node_position[corners[1]];
      const Eigen::Vector2d& c = m.node_position[corners[2]];
      // Bit i set: the side opposite corner i separates p from the region. All three tests are
      // made before branching, which keeps the unpredictable branches down to one per step.
      const unsigned separating = unsigned(orient2d(b, c, p) < 0) |
                                  unsigned(orient2d(c, a, p) < 0) << 1 |
                                  unsigned(orient2d(a, b, p) < 0) << 2;
      if (separating == 0) return {region};
      // Cross one of the separating sides, chosen at random when there are two (three is
      // impossible for a positively oriented triangle).
      const int side = chosen_side[separating][next_random() & 1u];
      const Index next = neighbors[static_cast<std::size_t>(region)][side];
      if (next == invalid_index) break;  // left D ∩ T here; p may still be in another part
      region = next;
    }
    return {detail::scan_regions(m, element, p)};
  }

 private:
  // chosen_side[mask][coin]: the side to cross when the sides in `mask` separate p. Masks 0
  // and 7 cannot occur here (7 only for a degenerate region; any valid side keeps it safe).
  static constexpr std::array<std::array<std::int8_t, 2>, 8> chosen_side = {
      {{0, 0}, {0, 0}, {1, 1}, {0, 1}, {2, 2}, {0, 2}, {1, 2}, {0, 1}}};

  // splitmix64 finalizer: spreads small seeds (0, 1, 2, ...) over the whole state space.
  // xorshift must never hold zero (it would stay there), so that one outcome is replaced.
  static std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x == 0 ? 0x2545f4914f6cdd1dULL : x;
  }

  // xorshift64*: a few cycles, 8 bytes of state, good enough to break walk cycles.
  std::uint32_t next_random() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return static_cast<std::uint32_t>((state_ * 0x2545f4914f6cdd1dULL) >> 32);
  }

  std::uint64_t state_;
};

static_assert(PointLocator<BrownFaigleWalk, 2>);

}  // namespace plmap::point_location
