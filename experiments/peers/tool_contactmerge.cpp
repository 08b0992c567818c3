// dune-grid-glue 2.9's ContactMerge (Debian libdune-grid-glue-dev) as one tool of the peer
// benchmark. Its build() is protected in ContactMerge and public in the Merger base, so it is
// called through the base. It needs S1's normals to face S2's (inputs.hpp orients them so).

#include "tools.hpp"

#include <dune/common/exceptions.hh>
#include <dune/geometry/type.hh>
#include <dune/grid-glue/merging/contactmerge.hh>
#include <dune/grid-glue/merging/merger.hh>

#include <cmath>
#include <exception>

namespace plmap::peers {

template <int d>
ToolOutcome run_contactmerge(const SurfacePair<d>& input, Measurement& clock) {
  constexpr int world = d + 1;
  using Coords = Dune::FieldVector<double, world>;
  ToolOutcome out;
  const auto convert = [](const PlainMesh<d>& mesh, std::vector<Coords>& coords, std::vector<unsigned>& cells,
                          std::vector<Dune::GeometryType>& types) {
    coords.resize(mesh.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      for (int k = 0; k < world; ++k) coords[i][k] = mesh.points[i][k];
    cells.clear();
    cells.reserve(mesh.cells.size() * (d + 1));
    for (const auto& c : mesh.cells)
      for (int k = 0; k <= d; ++k) cells.push_back(static_cast<unsigned>(c[k]));
    types.assign(mesh.cells.size(), Dune::GeometryTypes::simplex(d));
  };
  std::vector<Coords> coords1, coords2;
  std::vector<unsigned> cells1, cells2;
  std::vector<Dune::GeometryType> types1, types2;
  convert(input.s1, coords1, cells1, types1);
  convert(input.s2, coords2, cells2, types2);

  Dune::GridGlue::ContactMerge<world, double> contact;
  Dune::GridGlue::Merger<double, d, d, world>& merger = contact;
  try {
    clock.start();
    {
      QuietStdout quiet;
      merger.build(coords1, cells1, types1, coords2, cells2, types2);
    }
    clock.stop();
  } catch (const Dune::Exception& e) {
    clock.stop();
    out.error = e.what();
    return out;
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
    return out;
  }
  out.ok = true;
  const auto list = merger.intersectionList();
  out.pieces = static_cast<long>(list->size());
  double covered_target = 0.0;
  for (unsigned i = 0; i < list->size(); ++i) {
    // Measure relative to the parent cell: |det| of the local corners, as in tool_psurface.cpp.
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
    out.covered += relative(std::integral_constant<int, 0>{}) * input.s1.cell_measure(list->template parent<0>(i, 0));
    covered_target +=
        relative(std::integral_constant<int, 1>{}) * input.s2.cell_measure(list->template parent<1>(i, 0));
  }
  out.details = {{"covered_target", covered_target}, {"target_measure", input.s2.measure()}};
  return out;
}

template ToolOutcome run_contactmerge<1>(const SurfacePair<1>&, Measurement&);
template ToolOutcome run_contactmerge<2>(const SurfacePair<2>&, Measurement&);

}  // namespace plmap::peers
