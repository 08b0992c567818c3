#pragma once
// Inputs of the projection benchmark against the peers (experiments/peers/README.md): pairs of
// surfaces generated in memory from a seed, in a tool-neutral form (plain arrays), each with the
// exact measure of the overlap on S1 so that every tool's covered measure can be judged.
//
// Orientation: S1's normals point toward S2 and S2's point back toward S1 (a contact pair). This is
// what dune-grid-glue's ContactMerge needs (it compares n1·n2 <= -0.1) and what plmap's default
// (project along S1's normals, mu >= 0, no check of S2's normal) accepts as well.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace plmap::peers {

/// A simplicial surface as plain arrays: d = 1 polylines in the plane, d = 2 triangles in space.
template <int d>
struct PlainMesh {
  std::vector<std::array<double, d + 1>> points;
  std::vector<std::array<int, d + 1>> cells;

  /// Length (d = 1) or area (d = 2) of cell c.
  double cell_measure(std::size_t c) const;
  double measure() const;
};

template <int d>
struct SurfacePair {
  std::string family;  ///< plane, sphere, femur, circle
  std::string label;   ///< e.g. "plane 20000x33800"
  PlainMesh<d> s1, s2;
  /// Measure of the part of S1 that the exact normal projection covers.
  double exact_overlap = 0.0;
  /// Measure of the part of S2 that is the image of the covered part of S1.
  double exact_target_overlap = 0.0;
  std::string exact_overlap_note;
};

/// Facing planar patches: S1 = [0,1]^2 with n x n jittered cells, n chosen so that S1 has about
/// `s1_triangles` triangles; S2 = a shifted unit square [0.2,1.2] x [0.1,1.1] with about 1.3n x 1.3n
/// cells, a gap of half an S1 cell above. Exact overlap: 0.8 * 0.9.
SurfacePair<2> facing_planes(long s1_triangles, std::uint64_t seed);

/// Concentric spheres: S1 = geodesic icosphere of frequency 2^level (20 * 4^level triangles,
/// radius 1, outward); S2 = geodesic icosphere of frequency 2^level + 1, randomly rotated, radius
/// 1.01, inward. Exact overlap: all of S1.
SurfacePair<2> concentric_spheres(int level, std::uint64_t seed);

/// CGAL's femur (S1, as read) against a copy (S2) that is isotropically remeshed (if `remesh`; else
/// the same triangulation), whose vertices are moved out along the normals by 0.2 to 0.3 mean edge
/// lengths (random per vertex) and whose orientation is reversed. Exact overlap: all of S1 (a
/// closed surface inside a close offset of itself).
SurfacePair<2> femur_pair(const std::string& off_file, bool remesh, std::uint64_t seed);

/// Concentric circles: S1 with n segments, radius 1, counter-clockwise (outward normals); S2 with
/// round(1.3 n) segments, radius 1.01, rotated by a random angle, clockwise. Exact overlap: all of S1.
SurfacePair<1> concentric_circles(long s1_segments, std::uint64_t seed);

}  // namespace plmap::peers
