#pragma once
// Normal projection: the seeds of the searches of the ghost rays and the vertex preimages. Both
// start their walks from the elements whose centroids are nearest to a point. For the point
// itself, a kd-tree query costs O(gap / h) leaves when the point lies a gap of many element sizes
// away from the indexed surface (nanoflann bounds a subtree by its partition cell, which reaches
// right up to the query), e.g. 1,600 segment lengths on the 1M circles. Neighbouring items of a
// chunk have nearly the same offset to the other surface, so the search first asks for the
// centroids nearest to the point moved by the previous item's offset, which lies next to the
// indexed surface; only if that finds nothing does it ask at the point itself. Chunks have a
// fixed size, so the seeds, and the result, do not depend on the thread count.

#include "element_index.hpp"

#include <array>
#include <cstdint>

namespace plmap::projection {

/// Items (S1 vertices, S2 vertices) searched in one chunk, one after the other.
inline constexpr Index search_chunk = 256;

/// The most seeds one search takes (ProjectionOptions::search_seeds is clamped to it): the size
/// of the fixed seed arrays, which keep the searches free of allocations.
inline constexpr int max_search_seeds = 32;

using SeedElements = std::array<std::uint32_t, max_search_seeds>;

/// The k elements nearest to x; for the moved seed points of a curve from `nearest`. Along a
/// curve the moved seed points of consecutive items follow each other, and most answers come
/// from the centroids kept from an earlier, wider query. On a surface the vertex order is at
/// best row by row, and a wide query covers too few of the following points to pay (3 answers
/// from 21,000 queries on the L5 spheres): there the tree answers every query.
template <int d>
int nearest_seeds(const ElementIndex<d>& index, NearestElements<d>* nearest, const WorldPoint<d>& x, int k,
                  SeedElements& seeds) {
  if (d == 1 && nearest) return nearest->nearest(x, k, seeds);
  std::array<double, max_search_seeds> squared_distances;
  return index.nearest(x, k, seeds.data(), squared_distances.data());
}

}  // namespace plmap::projection
