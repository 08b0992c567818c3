#pragma once
/// \file
/// Error oracle that vetoes steps whose new triangles would intersect the rest of S1 (paper
/// 3.3.1: "reject simplification steps that lead to surface intersections"). Candidates come
/// from a Boost.Geometry R*-tree over the bounding boxes of the live S1 triangles (a box query
/// finds exactly the triangles whose boxes meet the new one's, however their sizes vary); the
/// test itself is CGAL's exact triangle–triangle intersection. Triangles sharing a vertex with
/// the new one are not tested (they meet there by construction); the index is kept up to date
/// by on_applied().

#include <plmap/strategies/simplification/error_oracle.hpp>

#include <memory>

namespace plmap {

class SelfIntersectionVeto {
 public:
  SelfIntersectionVeto();
  ~SelfIntersectionVeto();
  SelfIntersectionVeto(SelfIntersectionVeto&&) noexcept;
  SelfIntersectionVeto& operator=(SelfIntersectionVeto&&) noexcept;

  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
  void on_applied(const EditableMap& map, const VertexRemovalPlan& plan);

 private:
  struct Index;
  mutable std::unique_ptr<Index> index_;  // built on the first question, from the map asked about
};
static_assert(StatefulErrorOracle<SelfIntersectionVeto>);

}  // namespace plmap
