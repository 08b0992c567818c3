#pragma once
// What a smoothing step (quad_smoothing.hpp) hands from one of its phases to the next: the pieces
// of S2 edges in the quadrilateral, the rings of the unknowns, their new positions and the new
// crossings of the shared edge. Kept by the smoother between steps, so that the vectors' room is
// reused: one sweep runs a step per S1 edge, and allocating them per step was a tenth of the
// smoothing. Private to the smoothing.

#include "piece_crossings.hpp"
#include "preimage_graph.hpp"

#include <plmap/core/segment_sweep.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace plmap::smoothing {

/// A straight piece of an S2 edge inside the quadrilateral after the merge: from polyline point
/// `first` to `last` (the points between are crossings of e, dropped).
struct QuadPiece {
  Index edge;
  std::size_t first, last;
  std::array<int, 2> unknown{-1, -1};  ///< per end: unknown index, or -1 if fixed
  std::array<Index, 2> vertex{invalid_index, invalid_index};  ///< per end: S2 vertex, if it is one
  std::array<Eigen::Vector2d, 2> fixed{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};  ///< per fixed end: plane position
  std::array<double, 2> target_parameter{0.0, 0.0};
};

struct QuadStepWorkspace {
  // merge
  std::vector<QuadPiece> pieces;
  std::vector<char> inside;  ///< per segment of the S2 edge being merged: in T1 or T2
  // solve: per unknown, its pieces as (piece, end of the neighbour), the same in S2's cyclic
  // order, and the world positions of the neighbours on S2 in that order
  std::vector<std::vector<std::pair<int, int>>> ring_of, ordered_ring;
  std::vector<std::vector<Eigen::Vector3d>> ring_world;
  // checks: per unknown, its new and old plane position and new place
  std::vector<Eigen::Vector2d> position, old_position;
  std::vector<DomainPlace> new_place;
  std::vector<PlanarSegment> segments;
  std::vector<std::array<int, 2>> segment_ends;
  std::vector<PieceBox> boxes;
  // cut: per piece its new crossing of e, and bit 0 if it has a segment in T1 after the cut, bit
  // 1 in T2; per relevant S2 edge the same bits (QuadStepRecord::sides)
  std::vector<std::optional<EdgeCrossing>> cut;
  std::vector<std::uint8_t> piece_sides, edge_sides;
};

}  // namespace plmap::smoothing
