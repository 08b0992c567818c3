// PSurface 2.0's ContactMapping (Debian libpsurface-dev) as one tool of the peer benchmark. Its
// projection tests every pair of elements, so the driver caps its input size.

#include "tools.hpp"

#define PSURFACE_STANDALONE
#include <psurface/ContactMapping.h>

#include <cmath>
#include <exception>

namespace plmap::peers {

namespace {

/// Measure of a sub-simplex given by local coordinates on a cell, relative to the cell: the
/// determinant of the local corners (independent of which corner the local frame starts at).
template <int d, class Local>
double relative_measure(const Local& corners) {
  if constexpr (d == 1) {
    return std::abs(corners[1][0] - corners[0][0]);
  } else {
    const double ux = corners[1][0] - corners[0][0], uy = corners[1][1] - corners[0][1];
    const double vx = corners[2][0] - corners[0][0], vy = corners[2][1] - corners[0][1];
    return std::abs(ux * vy - uy * vx);
  }
}

}  // namespace

template <int d>
ToolOutcome run_psurface(const SurfacePair<d>& input, Measurement& clock) {
  constexpr int world = d + 1;
  ToolOutcome out;
  const auto convert = [](const PlainMesh<d>& mesh, auto& coords, auto& cells) {
    coords.resize(mesh.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      for (int k = 0; k < world; ++k) coords[i][k] = mesh.points[i][k];
    cells.resize(mesh.cells.size());
    for (std::size_t i = 0; i < mesh.cells.size(); ++i)
      for (int k = 0; k <= d; ++k) cells[i][k] = mesh.cells[i][k];
  };
  std::vector<std::tr1::array<double, world>> coords1, coords2;
  std::vector<std::tr1::array<int, d + 1>> cells1, cells2;
  convert(input.s1, coords1, cells1);
  convert(input.s2, coords2, cells2);

  std::vector<psurface::IntersectionPrimitive<d, double>> overlaps;
  try {
    clock.start();
    {
      QuietStdout quiet;
      psurface::ContactMapping<world, double> mapping;
      mapping.build(coords1, cells1, coords2, cells2);
      mapping.getOverlaps(overlaps);
    }
    clock.stop();
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
    return out;
  } catch (...) {
    // PSurface throws its own types (and plain strings) too.
    clock.stop();
    out.error = "PSurface threw a non-standard exception";
    return out;
  }
  out.ok = true;
  out.pieces = static_cast<long>(overlaps.size());
  double covered_target = 0.0;
  for (const auto& o : overlaps) {
    out.covered += relative_measure<d>(o.localCoords[0]) * input.s1.cell_measure(o.tris[0]);
    covered_target += relative_measure<d>(o.localCoords[1]) * input.s2.cell_measure(o.tris[1]);
  }
  out.details = {{"covered_target", covered_target}, {"target_measure", input.s2.measure()}};
  return out;
}

template ToolOutcome run_psurface<1>(const SurfacePair<1>&, Measurement&);
template ToolOutcome run_psurface<2>(const SurfacePair<2>&, Measurement&);

}  // namespace plmap::peers
