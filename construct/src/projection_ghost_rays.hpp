#pragma once
// Normal projection, phase 1: ghost rays. The ray v + t nu(v) from every S1 vertex v, cast against
// S2 by walks across S2 from the S2 elements nearest to v (or to the previous vertex's hit, see
// projection_seeds.hpp); the nearest admissible hit is v's image. The hits become ghost nodes
// (insertion) and seed the second search for vertex preimages.

#include "projection_context.hpp"

#include <optional>
#include <vector>

namespace plmap::projection {

/// Per S1 vertex: where its ray hits S2 first (admissible: distance and sign rules, normal check,
/// no focal point before the hit), or nothing. Independent of ctx.threads.
template <int d>
std::vector<std::optional<SurfacePoint<d>>> cast_rays_from_s1_vertices(const ProjectionContext<d>& ctx);

}  // namespace plmap::projection
