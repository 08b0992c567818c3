// projection_report_json: the one JSON form of a ProjectionResult's report
// (plmap/construct/projection_report_json.hpp).

#include <plmap/construct/projection_report_json.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace plmap {

template <int d>
nlohmann::ordered_json projection_report_json(const ProjectionResult<d>& result, std::size_t max_listed_edges) {
  const ProjectionReport<d>& r = result.report;
  nlohmann::ordered_json j;
  j["dimension"] = d;
  j["domain_measure"] = result.measures.domain;
  j["target_measure"] = result.measures.target;
  j["covered_measure"] = result.measures.covered_domain;
  j["covered_target_measure"] = result.measures.covered_target;
  j["regions"] = result.map.region_count();
  j["nodes"] = result.map.node_count();
  j["vertex_preimages"] = r.vertex_preimages;
  j["vertex_conflicts"] = r.vertex_conflicts;
  j["vertices_found_by_ray_hits"] = r.vertices_found_by_ray_hits;
  j["ghost_nodes"] = r.ghost_nodes;
  j["edges_inserted"] = r.edges_inserted;
  j["edges_partly_inserted"] = r.edges_partly_inserted;
  j["edges_outside"] = r.edges_outside;
  j["edges_not_inserted"] = r.edges_not_inserted.size();
  j["reversed_faces"] = r.reversed_faces;
  j["unmapped_faces"] = r.unmapped_faces;
  j["occluded_faces"] = r.occluded_faces;
  j["folded_faces"] = r.folded_faces;
  j["folded_regions_cut"] = r.folded_regions_cut;
  j["unbacked_regions"] = r.unbacked_regions;
  if constexpr (d == 2)  // the measure of S1 outside D, by why: with covered_measure, S1's measure
    for (const auto& [name, measure] : r.left_out.fields()) j["left_out_measure"][std::string(name)] = r.left_out.*measure;
  j["rim_nodes"] = r.rim_nodes;
  j["rim_edges"] = r.rim_edges;
  j["fold_rim_nodes"] = r.fold_rim_nodes;
  j["fold_rim_edges"] = r.fold_rim_edges;
  nlohmann::ordered_json listed = nlohmann::ordered_json::array();
  const std::size_t count = std::min(max_listed_edges, r.edges_not_inserted.size());
  for (std::size_t i = 0; i < count; ++i) {
    const EdgeNotInserted<d>& e = r.edges_not_inserted[i];
    listed.push_back({{"target_edge", e.target_edge},
                      {"reason", std::string(to_string(e.reason))},
                      {"domain_element", e.domain_element},
                      {"domain_point", std::vector<double>(e.domain_point.data(), e.domain_point.data() + d + 1)},
                      {"target_parameter", e.target_parameter},
                      {"detail", e.detail}});
  }
  j["edges_not_inserted_list"] = std::move(listed);
  j["renumbered"] = {{"S1", r.renumbered_domain}, {"S2", r.renumbered_target}};
  j["solver_calls"] = r.solver_calls;
  j["solver_failures"] = r.solver_failures;
  j["seconds"] = r.seconds.total;
  j["seconds_by_phase"] = {{"setup", r.seconds.setup},
                           {"vertex_preimages", r.seconds.vertex_preimages},
                           {"ghost_nodes", r.seconds.ghost_nodes},
                           {"edge_walks", r.seconds.edge_walks},
                           {"insertion", r.seconds.insertion},
                           {"finalize", r.seconds.finalize},
                           {"renumbering", r.seconds.renumbering}};
  return j;
}

template nlohmann::ordered_json projection_report_json<1>(const ProjectionResult<1>&, std::size_t);
template nlohmann::ordered_json projection_report_json<2>(const ProjectionResult<2>&, std::size_t);

}  // namespace plmap
