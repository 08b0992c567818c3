// Normal projection, phase 5: the nodes where pieces meet the sheet beyond a fold, and the fold
// rim between them (projection_fold_rim.hpp; ProjectionInsertion, insert_fold_rims).

#include "projection_insertion.hpp"

#include <plmap/core/errors.hpp>


namespace plmap::projection {

template <int d>
Index ProjectionInsertion<d>::fold_rim_node(const RimPoint<d>& point, Index e) {
  if constexpr (d == 2) {
    // (as rim_node_inside: not within rounding of the edge's ends)
    if (!(point.eta > rim_margin && point.eta < 1.0 - rim_margin)) return invalid_index;
    try {
      const Index node = builder_.add_rim_node({point.element, point.local}, point_on_target_edge(e, point.eta));
      ++rim_nodes_made_;
      return node;
    } catch (const BuilderError&) {
      // e.g. the point snaps onto a node already there
    }
  }
  return invalid_index;
}

template <int d>
void ProjectionInsertion<d>::insert_fold_rims(std::span<const FoldRimPath> paths, ProjectionReport<d>& report) {
  if constexpr (d == 2) {
    // a chain of rim edges from one meeting node to the other; a node or edge the builder refuses
    // ends the chain there (finalize drops rim edges that cross others, and what is left of the
    // chain then bounds no face of its own)
    for (const FoldRimPath& path : paths) {
      Index previous = path.from;
      bool whole = true;
      for (const FoldRimCrossing& c : path.crossings) {
        const Index node = rim_node_on_edge(c.domain_edge, c.lambda, path.target, c.image);
        whole = node != invalid_index && add_fold_rim_edge(previous, node, report);
        if (!whole) break;
        previous = node;
      }
      if (whole) add_fold_rim_edge(previous, path.to, report);
    }
    report.fold_rim_nodes = static_cast<Index>(fold_points_.size());
    report.rim_nodes = rim_nodes_made_;
    std::vector<FoldRimNode>().swap(fold_points_);
  }
}

template <int d>
bool ProjectionInsertion<d>::add_fold_rim_edge(Index a, Index b, ProjectionReport<d>& report) {
  if constexpr (d == 2) {
    try {
      builder_.add_rim_edge(a, b);
      ++report.fold_rim_edges;
      return true;
    } catch (const BuilderError&) {
    }
  }
  return false;
}

#define PLMAP_FOLD_RIM_MEMBERS(d)                                                                                 \
  template Index ProjectionInsertion<d>::fold_rim_node(const RimPoint<d>&, Index);                                \
  template void ProjectionInsertion<d>::insert_fold_rims(std::span<const FoldRimPath>, ProjectionReport<d>&);     \
  template bool ProjectionInsertion<d>::add_fold_rim_edge(Index, Index, ProjectionReport<d>&);
PLMAP_FOLD_RIM_MEMBERS(1)
PLMAP_FOLD_RIM_MEMBERS(2)
#undef PLMAP_FOLD_RIM_MEMBERS

}  // namespace plmap::projection
