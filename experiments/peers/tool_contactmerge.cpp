// dune-grid-glue 2.9's ContactMerge (Debian libdune-grid-glue-dev) as one tool of the peer
// benchmark. Its build() is protected in ContactMerge and public in the Merger base, so it is
// called through the base. It needs S1's normals to face S2's (inputs.hpp orients them so).

#include "dune_contact.hpp"
#include "tools.hpp"

#include <dune/common/exceptions.hh>
#include <dune/grid-glue/merging/contactmerge.hh>
#include <dune/grid-glue/merging/merger.hh>

#include <exception>

namespace plmap::peers {

template <int d>
ToolOutcome run_contactmerge(const SurfacePair<d>& input, Measurement& clock) {
  constexpr int world = d + 1;
  ToolOutcome out;
  const DuneSimplices<d> s1 = to_dune_simplices(input.s1), s2 = to_dune_simplices(input.s2);
  Dune::GridGlue::ContactMerge<world, double> contact;
  Dune::GridGlue::Merger<double, d, d, world>& merger = contact;
  try {
    clock.start();
    {
      QuietStdout quiet;
      merger.build(s1.coords, s1.cells, s1.types, s2.coords, s2.cells, s2.types);
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
  out.pieces = static_cast<long>(merger.intersectionList()->size());
  const OverlapMeasures covered = overlap_measures(merger, input);
  out.covered = covered.s1;
  out.details = {{"covered_target", covered.s2}, {"target_measure", input.s2.measure()}};
  return out;
}

template ToolOutcome run_contactmerge<1>(const SurfacePair<1>&, Measurement&);
template ToolOutcome run_contactmerge<2>(const SurfacePair<2>&, Measurement&);

}  // namespace plmap::peers
