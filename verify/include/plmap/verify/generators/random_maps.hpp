#pragma once
/// \file
/// Valid piecewise-linear maps with known answers, built through MapBuilder:
///
/// - identity: S2 = S1, every vertex its own preimage, every element mapped onto itself;
/// - refinement: S2 a random refinement of S1 (random points on S1's edges, shared by all
///   triangles of an edge, and inside its elements); Xi^{-1} is the inclusion S2 -> S1;
/// - overlay: S1 and S2 two independent triangulations of the same planar domain (d = 2) or two
///   subdivisions of the same polyline (d = 1); Xi is the identity of the plane. The generator
///   locates every S2 vertex on S1 and every S1 vertex on S2 and lists, for every S2 edge, the S1
///   edges it crosses, with exact predicates, so the builder gets intersection nodes, ghost nodes,
///   touching nodes and edges through S1 vertices (automatic ghost nodes).
///
/// In all three cases Xi is the identity of the ambient space: Xi(x) = x for every x in S1, D = S1
/// and Xi(D) = S2. Tests use that as the oracle.
///
/// Plain functions with a random engine; rc_generators.hpp wraps them as rc::Gen.

#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <memory>
#include <string>
#include <vector>

namespace plmap::generators {

/// A map together with what the generator knows about it.
template <int d>
struct MapCase {
  std::string description;  ///< how it was made (kind, sizes, seed), for failure messages
  std::shared_ptr<const Surface<d>> domain;  ///< S1
  std::shared_ptr<const Surface<d>> target;  ///< S2
  std::shared_ptr<const PlMap<d>> map;
  /// For every S2 vertex, its preimage on S1 as handed to the builder (element + local coords);
  /// no_preimage() for an isolated S2 vertex (one no element uses: not part of the surface).
  std::vector<SurfacePoint<d>> target_vertex_preimage;
};

/// The entry of MapCase::target_vertex_preimage for an isolated S2 vertex: element invalid_index.
template <int d>
SurfacePoint<d> no_preimage() {
  return {invalid_index, LocalPoint<d>::Zero()};
}

/// Where a point of S1 lies, combinatorially, and as a point on one of its elements.
template <int d>
struct DomainLocation {
  /// isolated: an S1 vertex that no element uses, so no point of S1 (it gets no preimage).
  enum class Kind { vertex, edge, element, isolated };
  Kind kind = Kind::element;
  Index index = invalid_index;  ///< S1 vertex / S1 edge (d = 2) / S1 element, by kind
  double edge_parameter = 0.0;  ///< on the edge, from its smaller-index vertex (kind == edge)
  SurfacePoint<d> point;        ///< always set (no_preimage() for kind isolated)
};

/// Enters the preimage of S2 vertex `target_vertex` with the builder call that fits `where`.
template <int d>
void add_vertex_preimage(MapBuilder<d>& builder, Index target_vertex, const DomainLocation<d>& where);

// ---- identity ------------------------------------------------------------------------------------

template <int d>
MapCase<d> identity_map(std::shared_ptr<const Surface<d>> surface, std::string description = "identity");

// ---- refinement ----------------------------------------------------------------------------------

struct RefinementOptions {
  int max_points_per_edge = 2;     ///< each S1 edge (d = 2) gets 0..max points
  int max_points_per_element = 3;  ///< each S1 element gets 0..max interior points
};

/// A refinement of S1 and where each of its vertices lies on S1.
template <int d>
struct Refinement {
  Surface<d> refined;
  std::vector<DomainLocation<d>> vertex_location;  ///< per vertex of `refined`
};

/// Splits every S1 element by random points on its edges (d = 2, shared by all triangles of the
/// edge) and in its interior; d = 2 triangulates each element's points by Delaunay in local
/// coordinates. Edge parameters are dyadic (multiples of 1/64), so points on the slanted local
/// edge are exactly on it and the local triangulation has no slivers. Elements of the
/// refinement keep the orientation of their S1 element.
template <int d>
Refinement<d> random_refinement(const Surface<d>& s1, const RefinementOptions& options, Rng& rng);

/// Uniform refinement, as `plmap build refine` makes it: every segment split into 2^levels equal
/// pieces (d = 1), every triangle into 4^levels similar triangles (d = 2). Throws plmap::Error if
/// levels is outside [0, 20] or the result would have more than `max_elements` elements.
template <int d>
Refinement<d> uniform_refinement(const Surface<d>& s1, int levels, Index max_elements);

/// The inclusion map of a refinement: S1 -> S2 = refinement.refined.
template <int d>
MapCase<d> refinement_map(std::shared_ptr<const Surface<d>> s1, const Refinement<d>& refinement,
                          std::string description = "refinement");

// ---- overlay -------------------------------------------------------------------------------------

/// Xi = identity of the plane between two triangulations of the same planar domain (z = 0,
/// counter-clockwise triangles). Throws plmap::Error if a vertex of one surface is not on the
/// other or a surface is not planar. Brute force (|E1| * |E2| exact orientation tests): meant
/// for test-sized surfaces.
MapCase<2> plane_overlay_map(std::shared_ptr<const Surface<2>> s1, std::shared_ptr<const Surface<2>> s2,
                             std::string description = "overlay");

/// Two subdivisions of the same polyline, known by parameters along its segments.
struct PolylineSubdivisions {
  std::shared_ptr<const Surface<1>> base;
  /// Per base segment, the interior split parameters (sorted, in (0, 1)) of S1 and of S2.
  std::vector<std::vector<double>> s1_splits, s2_splits;
};

/// Random split parameters for both subdivisions; with probability 1/2 per point a parameter
/// is a multiple of 1/8, so S1 and S2 often share vertices.
PolylineSubdivisions random_subdivisions(std::shared_ptr<const Surface<1>> base, int max_splits,
                                         Rng& rng);

/// Xi = identity of the plane between the two subdivisions (S1 from s1_splits, S2 from
/// s2_splits); shared parameters give shared vertices, the others ghost nodes and crossings.
MapCase<1> polyline_overlay_map(const PolylineSubdivisions& subdivisions,
                                std::string description = "overlay");

/// The polyline split at the given parameters (one list per base segment), segments keeping
/// the direction of their base segment.
Surface<1> subdivide_polyline(const Surface<1>& base, const std::vector<std::vector<double>>& splits);

}  // namespace plmap::generators
