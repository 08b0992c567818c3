// plmap's normal projection (construct/project.hpp) as one tool of the peer benchmark.

#include "plain_mesh_surface.hpp"
#include "tools.hpp"

#include <plmap/construct/project.hpp>

#include <exception>
#include <stdexcept>
#include <string>
#include <memory>

namespace plmap::peers {

namespace {

SpatialRenumbering renumbering_from(const std::string& name) {
  if (const auto r = spatial_renumbering_from_name(name)) return *r;
  throw std::invalid_argument("unknown --renumber '" + name + "' (auto, always, target or never)");
}

}  // namespace

template <int d>
ToolOutcome run_plmap(const SurfacePair<d>& input, unsigned threads, const std::string& renumbering,
                      Measurement& clock) {
  ToolOutcome out;
  const auto s1 = to_surface(input.s1);
  const auto s2 = to_surface(input.s2);
  ProjectionOptions options;
  options.threads = threads;
  options.renumbering = renumbering_from(renumbering);
  try {
    clock.start();
    const ProjectionResult<d> result = project<d>(s1, s2, options);
    clock.stop();
    const auto& r = result.report;
    out.ok = true;
    out.covered = result.measures.covered_domain;
    out.pieces = result.map.region_count();
    out.details = {{"covered_target", result.measures.covered_target},
                   {"target_measure", result.measures.target},
                   {"nodes", result.map.node_count()},
                   {"vertex_preimages", r.vertex_preimages},
                   {"target_vertices", r.target_vertices},
                   {"edges_inserted", r.edges_inserted},
                   {"edges_partly_inserted", r.edges_partly_inserted},
                   {"edges_not_inserted", r.edges_not_inserted.size()},
                   {"solver_failures", r.solver_failures},
                   {"seconds_by_phase",
                    {{"setup", r.seconds.setup},
                     {"vertex_preimages", r.seconds.vertex_preimages},
                     {"ghost_nodes", r.seconds.ghost_nodes},
                     {"edge_walks", r.seconds.edge_walks},
                     {"insertion", r.seconds.insertion},
                     {"finalize", r.seconds.finalize},
                     {"renumbering", r.seconds.renumbering},
                     {"total", r.seconds.total}}},
                   {"renumbered", {{"S1", r.renumbered_domain}, {"S2", r.renumbered_target}}}};
    if (!r.edges_not_inserted.empty()) {
      const auto& e = r.edges_not_inserted.front();
      out.details["first_edge_not_inserted"] = {{"target_edge", e.target_edge},
                                                {"reason", std::string(to_string(e.reason))},
                                                {"domain_element", e.domain_element},
                                                {"detail", e.detail}};
    }
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
  }
  return out;
}

template ToolOutcome run_plmap<1>(const SurfacePair<1>&, unsigned, const std::string&, Measurement&);
template ToolOutcome run_plmap<2>(const SurfacePair<2>&, unsigned, const std::string&, Measurement&);

}  // namespace plmap::peers
