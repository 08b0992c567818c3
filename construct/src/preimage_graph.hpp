#pragma once
// PreimageGraph: a parametrization Ξ: S1 → S2 in the form MapBuilder takes as input, the form
// in which quadrilateral smoothing moves vertex preimages across S1 edges. Per S2 vertex: where
// its preimage lies on S1 (an S1 vertex, a point of an S1 edge, a point inside an S1 element).
// Per S2 edge: the S1 edges its preimage crosses, in order from its smaller-index vertex, each
// with where it lands on the S2 edge. Segments between consecutive points are straight in their
// S1 element; the element's graph and triangular closure are MapBuilder's job (to_map).
//
// Only maps that are parametrizations in this simple sense can be put in this form: every S2
// vertex has a preimage, every S2 edge a complete preimage, and no S1 vertex is a ghost node
// (S1's vertices are vertex preimages, as for a simplification-built map). from_map says why
// otherwise.

#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace plmap::smoothing {

/// Where a point of S2's edge graph lies on S1.
struct DomainPlace {
  enum class Kind : std::uint8_t { vertex, edge, element };
  Kind kind = Kind::element;
  Index where = invalid_index;  ///< S1 vertex, S1 edge or S1 element
  double edge_parameter = 0.0;  ///< kind edge: 0 at the edge's smaller-index vertex
  LocalPoint<2> local = LocalPoint<2>::Zero();  ///< kind element
};

struct PreimageGraph {
  std::vector<DomainPlace> vertex;                 ///< per S2 vertex
  std::vector<std::vector<EdgeCrossing>> crossings;  ///< per S2 edge, increasing target_parameter
  int orientation = 1;

  /// The graph of `map`, or nothing with `why` set when the map is not in the simple form.
  static std::optional<PreimageGraph> from_map(const PlMap<2>& map, std::string* why);
  /// The map through MapBuilder (which closes every element). Throws BuilderError when the
  /// graph is inconsistent (crossing edges).
  PlMap<2> to_map(const std::shared_ptr<const Surface<2>>& domain, const std::shared_ptr<const Surface<2>>& target,
                  FinalizeReport* report) const;
  /// The same map, with every element t with reuse[t] != 0 copied from `previous` instead of
  /// closed again (MapBuilder::finalize_reusing): `previous` must be to_map of a graph that is
  /// this one on those elements (their vertex preimages, the crossings of their edges).
  PlMap<2> to_map_reusing(const std::shared_ptr<const Surface<2>>& domain, const std::shared_ptr<const Surface<2>>& target,
                          const PlMap<2>& previous, std::span<const char> reuse, FinalizeReport* report) const;

 private:
  MapBuilder<2> builder(const std::shared_ptr<const Surface<2>>& domain, const std::shared_ptr<const Surface<2>>& target) const;
};

/// Point i of the preimage of S2 edge `edge`: 0 is the preimage of its smaller-index vertex,
/// 1..m the crossings, m + 1 the preimage of the larger-index vertex.
DomainPlace polyline_point(const PreimageGraph& g, const Surface<2>& target, Index edge, std::size_t i);
/// Where that point lands on the S2 edge (0 at its smaller-index vertex).
double polyline_target_parameter(const PreimageGraph& g, Index edge, std::size_t i);
inline std::size_t polyline_size(const PreimageGraph& g, Index edge) { return g.crossings[edge].size() + 2; }

/// The S1 element that contains both places, if exactly one does; invalid_index if none;
/// `along_edge` is set when several do (both places on one S1 edge).
Index common_element(const Surface<2>& domain, const DomainPlace& a, const DomainPlace& b, bool* along_edge);

}  // namespace plmap::smoothing
