#pragma once
// Normal projection, phase 2: vertex preimages (paper eq. 3). For every S2 vertex q, solve
// p(xi) + mu nu(xi) = q on S1 elements, walking across S1 from the elements nearest to q towards
// the solution; among the admissible solutions the nearest wins. A second search seeds the
// walks for the S2 vertices still without a preimage from the ghost rays' hits next to q.

#include "projection_context.hpp"

#include <optional>
#include <vector>

namespace plmap::projection {

template <int d>
struct VertexPreimages {
  /// Per S2 vertex: its preimage on S1, or nothing.
  std::vector<std::optional<SurfacePoint<d>>> preimage;
  /// How many of them only the second search, seeded from the ray hits, found.
  Index found_by_ray_hits = 0;
};

/// How many of a search's seeds are walked from. The answer is the same either way
/// (preimage_rank_floor.hpp explains why); `all` is for the tests that show it.
enum class SeedWalks {
  /// stop once no element on which a nearer preimage could be accepted is left unsolved
  until_no_rival_left,
  /// walk from every seed
  all,
};

/// The preimages of all S2 vertices. `ray_hits` are the ghost rays' hits (per S1 vertex).
/// Independent of ctx.threads.
template <int d, class Solver>
VertexPreimages<d> find_vertex_preimages(const ProjectionContext<d>& ctx, const Solver& solver,
                                         const std::vector<std::optional<SurfacePoint<d>>>& ray_hits,
                                         SeedWalks walks = SeedWalks::until_no_rival_left);

}  // namespace plmap::projection
