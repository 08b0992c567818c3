#pragma once
// What the Dune mergers need from a contact pair and what they give back, shared by
// tool_contactmerge.cpp (ContactMerge as a tool of bench_projection_peers) and
// experiments/dune_merger (ContactMerge against plmap's PlmapMerge): the pair as dune-grid-glue's
// build() takes it, and the overlap measure on both sides from the merger's intersection list.
// Header-only: only targets built with dune-grid-glue include it.

#include "inputs.hpp"

#include <dune/common/fvector.hh>
#include <dune/geometry/type.hh>

#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace plmap::peers {

/// One surface in the arrays of `Merger::build`: coordinates, corner indices, element types.
template <int d>
struct DuneSimplices {
  std::vector<Dune::FieldVector<double, d + 1>> coords;
  std::vector<unsigned> cells;
  std::vector<Dune::GeometryType> types;
};

template <int d>
DuneSimplices<d> to_dune_simplices(const PlainMesh<d>& mesh) {
  DuneSimplices<d> out;
  out.coords.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int k = 0; k <= d; ++k) out.coords[i][k] = mesh.points[i][k];
  out.cells.reserve(mesh.cells.size() * (d + 1));
  for (const auto& c : mesh.cells)
    for (int k = 0; k <= d; ++k) out.cells.push_back(static_cast<unsigned>(c[k]));
  out.types.assign(mesh.cells.size(), Dune::GeometryTypes::simplex(d));
  return out;
}

/// The sums of the overlap simplices' measures on S1 and on S2.
struct OverlapMeasures {
  double s1 = 0.0, s2 = 0.0;
};

/// The overlap measures of a built merger's intersection list. Each simplex's measure is its
/// measure in the local coordinates of its parent cell (|det| of the local corners) times the
/// parent's measure, as tool_psurface.cpp measures PSurface's.
template <int d, class Merger>
OverlapMeasures overlap_measures(const Merger& merger, const SurfacePair<d>& pair) {
  OverlapMeasures out;
  const auto list = merger.intersectionList();
  for (unsigned i = 0; i < list->size(); ++i) {
    const auto relative = [&](auto side) {
      constexpr int n = decltype(side)::value;
      const auto c0 = list->template corner<n>(i, 0, 0);
      const auto c1 = list->template corner<n>(i, 1, 0);
      if constexpr (d == 1) {
        return std::abs(c1[0] - c0[0]);
      } else {
        const auto c2 = list->template corner<n>(i, 2, 0);
        return std::abs((c1[0] - c0[0]) * (c2[1] - c0[1]) - (c1[1] - c0[1]) * (c2[0] - c0[0]));
      }
    };
    out.s1 += relative(std::integral_constant<int, 0>{}) * pair.s1.cell_measure(list->template parent<0>(i, 0));
    out.s2 += relative(std::integral_constant<int, 1>{}) * pair.s2.cell_measure(list->template parent<1>(i, 0));
  }
  return out;
}

}  // namespace plmap::peers
