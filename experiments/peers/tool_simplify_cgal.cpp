// The floor of the simplification benchmark: CGAL's edge-collapse simplification
// (Surface_mesh_simplification, Lindstrom-Turk placement and cost), which decimates without
// keeping a map, on the same mesh to the same number of triangles.

#include "simplification_tools.hpp"

#include <plmap/verify/generators/simplified_surface.hpp>

#include <exception>

namespace plmap::peers {

SimplificationOutcome simplify_with_cgal(const SimplificationRequest& request, Measurement& clock) {
  SimplificationOutcome out;
  double cpu_start = 0.0;
  bool collapsing = false;
  // verify's conversion and collapse; the clocks run around CGAL's collapse alone
  const auto start = [&] {
    clock.start();
    cpu_start = process_cpu_seconds();
    collapsing = true;
  };
  const auto stop = [&] {
    out.cpu_simplify = process_cpu_seconds() - cpu_start;
    clock.stop();
    collapsing = false;
  };
  Surface<2> coarse;
  try {
    coarse = generators::simplify_by_edge_collapse(*request.fine, std::size_t(request.target_elements),
                                                   {.before_collapse = start, .after_collapse = stop});
  } catch (const std::exception& e) {
    if (collapsing) clock.stop();
    out.error = e.what();  // a non-manifold mesh is refused before the clock starts
    return out;
  }
  out.seconds_simplify = clock.seconds();
  out.figures["elements"] = coarse.element_count();
  out.figures["vertices"] = coarse.vertex_count();
  out.figures["coarse_aspect"] = aspect_ratio_json(coarse);
  out.ok = true;
  return out;
}

}  // namespace plmap::peers
