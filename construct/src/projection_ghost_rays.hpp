#pragma once
// Normal projection, phase 1: ghost rays. The ray v + t nu(v) from every S1 vertex v, cast against
// S2 by walks across S2 from the S2 elements nearest to v (or to the previous vertex's hit, see
// projection_seeds.hpp); the nearest admissible hit is v's image. The hits become ghost nodes
// (insertion) and seed the second search for vertex preimages.

#include "projection_context.hpp"

#include <cstdint>

#include <optional>
#include <vector>

namespace plmap::projection {

/// Per S1 vertex: where its ray hits S2 first (admissible: distance and sign rules, normal check,
/// no focal point before the hit), or nothing. Independent of ctx.threads. If `outside_band` is
/// given, it receives per S1 vertex without an admissible hit whose ray meets S2 only outside
/// the band of admissible distances the distance of that hit (the first found), and NaN for
/// every other vertex: where neighbours lie on different sides of a bound, the rim of D crosses
/// the S1 edge between them (the rim's seeds, projection_rim.cpp).
template <int d>
std::vector<std::optional<SurfacePoint<d>>> cast_rays_from_s1_vertices(const ProjectionContext<d>& ctx,
                                                                      std::vector<float>* outside_band = nullptr);

}  // namespace plmap::projection
