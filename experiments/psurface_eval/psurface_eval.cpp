// plmap against PSurface 2.0 on the same maps, in the same process (results and method in
// experiments/psurface_eval/README.md).
//
// For every case a plmap map is built (femur-like refinement maps as in bench_point_location,
// a projection-built sphere map, or any .plmap file given with --map) and entered, node by node
// and edge by edge, into a psurface::PSurface<2, ctype> for ctype = double and float. Then:
//  - evaluations per CPU-second of PSurface::map() and of plmap's evaluate_batch with every
//    registered point locator, on one thread, on the same stream of random queries (element
//    uniform, point uniform in the element, fixed seed), median of three repetitions;
//  - the agreement of the two images (same S2 point up to 1e-9, 1e-6 and 1e-3 of S2's bounding
//    box diagonal) on every query;
//  - memory per graph node: for PSurface the heap bytes its graph occupies (mallinfo2 difference
//    around the graph construction, the two surfaces excluded) and, for reference, the bytes its
//    graph arrays hold by size; for plmap PlMap::memory_bytes() of the compact form.
//
// How the map enters PSurface: the domain surface through PSurfaceFactory::insertVertex and
// insertSimplex, the target surface as a psurface::Surface, every node through the factory's
// addCornerNode / addGhostNode / addTouchingNode / addInteriorNode / addIntersectionNodePair
// (one call per pair of copies on a shared S1 edge), every graph edge through
// DomainTriangle::addEdge with plmap's closure flag (PSurfaceFactory::insertEdge() is an empty
// stub in PSurface 2.0 and addParTriangle marks every edge as regular), the edgePoints arrays
// from plmap's edge arrays, iPos = S2 vertex positions followed by the intersection points. The
// graph is already triangulated, so only the per-triangle part of
// PSurface::createPointLocationStructure() runs; its closure step (insertExtraEdges) is run on a
// copy for the record (edges it adds, and the agreement of map() afterwards).
//
// Usage: psurface_eval [--femur femur.off] [--map file.plmap]... [--no-sphere]
//                      [--queries N] [--json out.json]

#include "../../tests/construct/projection_fixtures.hpp"
#include "evaluation_cases/evaluation_cases.hpp"
#include "peers/measurement.hpp"
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <plmap/construct/project.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/strategies/point_locator_registry.hpp>

// PSURFACE_STANDALONE is defined by the build (the headers need it).
#include <psurface/PSurface.h>
#include <psurface/PSurfaceFactory.h>
#include <psurface/TargetSurface.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <malloc.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace plmap;
using Json = nlohmann::json;

/// CPU seconds of work(), median of three runs.
template <class Work>
double median_cpu_seconds(Work&& work) {
  std::array<double, 3> t{};
  for (double& s : t) {
    const double t0 = peers::process_cpu_seconds();
    work();
    s = peers::process_cpu_seconds() - t0;
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

std::size_t heap_in_use() { return mallinfo2().uordblks; }

// ---- maps --------------------------------------------------------------------------------------

struct Case {
  std::string name;
  std::shared_ptr<const PlMap<2>> map;
};

// ---- the same map in PSurface ------------------------------------------------------------------

/// PSurface's local coordinates on a triangle are (lambda_0, lambda_1): corner 0 at (1, 0),
/// corner 1 at (0, 1), corner 2 at (0, 0). plmap's local (x, y) has barycentric (1-x-y, x, y).
template <class ctype>
psurface::StaticVector<ctype, 2> to_psurface_local(const LocalPoint<2>& xi) {
  return psurface::StaticVector<ctype, 2>(ctype(1 - xi(0) - xi(1)), ctype(xi(0)));
}

/// For each intersection node its copy on the other triangle of the S1 edge (invalid on boundary
/// or non-manifold edges, where PSurface has no partner either).
std::vector<Index> intersection_partners(const PlMap<2>& map) {
  const auto& s1 = map.domain();
  const auto& m = map.data();
  std::vector<Index> partner(std::size_t(map.node_count()), invalid_index);
  for (Index t = 0; t < s1.element_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto nodes = map.edge_nodes(t, k);
      const auto incident = s1.edge_elements(s1.element_edge(t, k));
      if (incident.size() != 2) continue;
      const EdgeIncidence other = incident[0].element == t ? incident[1] : incident[0];
      const auto other_nodes = map.edge_nodes(other.element, other.local_edge);
      if (other_nodes.size() != nodes.size())
        throw Error(fmt::format("S1 edge {}: the two copies of its edge array differ in length",
                                s1.element_edge(t, k)));
      const bool same_direction = s1.element(t)[k] == s1.element(other.element)[other.local_edge];
      for (std::size_t j = 1; j + 1 < nodes.size(); ++j) {
        if (m.node_type[nodes[j]] != NodeType::intersection) continue;
        const std::size_t j2 = same_direction ? j : nodes.size() - 1 - j;
        partner[nodes[j]] = other_nodes[j2];
      }
    }
  return partner;
}

template <class ctype>
struct PSurfaceMap {
  std::unique_ptr<psurface::Surface> target;
  std::unique_ptr<psurface::PSurface<2, ctype>> psurface;
  /// The same graph after PSurface's own createPointLocationStructure(), closure step included.
  std::unique_ptr<psurface::PSurface<2, ctype>> own_closure;
  std::size_t target_heap_bytes = 0;   ///< the psurface::Surface (S2)
  std::size_t domain_heap_bytes = 0;   ///< vertices, edges, triangle records of S1
  std::size_t graph_heap_bytes = 0;    ///< nodes, neighbour lists, edgePoints, iPos
  std::size_t graph_payload_bytes = 0; ///< the same by size (no capacity slack, no malloc headers)
  std::size_t nodes = 0;
  std::size_t edges_before_closure = 0;
  std::size_t edges_added_by_psurface = 0;
  std::size_t ghost_nodes = 0;
  std::size_t intersection_nodes = 0;
  double build_seconds = 0;
};

template <class ctype>
std::size_t count_graph_edges(const psurface::PSurface<2, ctype>& ps) {
  std::size_t n = 0;
  for (std::size_t t = 0; t < ps.getNumTriangles(); ++t) n += ps.triangles(int(t)).getNumEdges();
  return n;
}

template <class ctype>
PSurfaceMap<ctype> build_psurface(const PlMap<2>& map) {
  using V3 = psurface::StaticVector<ctype, 3>;
  const auto& s1 = map.domain();
  const auto& s2 = map.target();
  const auto& m = map.data();
  PSurfaceMap<ctype> out;
  // PSurface's graph has no node where the map stops inside an S1 element.
  for (Index n = 0; n < map.node_count(); ++n)
    if (is_on_rim(m.node_type[n]))
      throw Error(fmt::format("node {} lies on the rim of D inside S1 (a {} node): PSurface 2.0 has no such node, "
                              "so this map cannot be converted",
                              n, to_string(m.node_type[n])));

  // Everything the translation needs is computed before the heap is measured.
  const std::vector<Index> partner = intersection_partners(map);
  std::vector<int> local_index(std::size_t(map.node_count()), -1);

  const double t0 = peers::process_cpu_seconds();
  const std::size_t heap0 = heap_in_use();
  out.target = std::make_unique<psurface::Surface>();
  out.target->points.resize(std::size_t(s2.vertex_count()));
  for (Index v = 0; v < s2.vertex_count(); ++v)
    for (int i = 0; i < 3; ++i) out.target->points[std::size_t(v)][i] = float(s2.vertex(v)(i));
  out.target->triangles.resize(std::size_t(s2.element_count()));
  for (Index e = 0; e < s2.element_count(); ++e)
    for (int i = 0; i < 3; ++i) out.target->triangles[std::size_t(e)].points[i] = s2.element(e)[i];
  const std::size_t heap1 = heap_in_use();

  out.psurface = std::make_unique<psurface::PSurface<2, ctype>>();
  auto& ps = *out.psurface;
  ps.hasUpToDatePointLocationStructure = false;
  psurface::PSurfaceFactory<2, ctype> factory(&ps);
  factory.setTargetSurface(out.target.get());
  for (Index v = 0; v < s1.vertex_count(); ++v) {
    const auto& x = s1.vertex(v);
    factory.insertVertex(V3(ctype(x(0)), ctype(x(1)), ctype(x(2))));
  }
  for (Index t = 0; t < s1.element_count(); ++t) {
    const auto& c = s1.element(t);
    const unsigned idx = factory.insertSimplex({unsigned(c[0]), unsigned(c[1]), unsigned(c[2])});
    if (idx != unsigned(t)) throw Error(fmt::format("PSurface numbered triangle {} as {}", t, idx));
  }
  const std::size_t heap2 = heap_in_use();

  // iPos: the S2 vertices (node numbers of corner, touching and interior nodes), then one entry
  // per intersection point (appended by addIntersectionNodePair).
  ps.iPos.reserve(std::size_t(s2.vertex_count()));
  for (Index v = 0; v < s2.vertex_count(); ++v) {
    const auto& x = s2.vertex(v);
    ps.iPos.push_back(V3(ctype(x(0)), ctype(x(1)), ctype(x(2))));
  }
  for (Index t = 0; t < s1.element_count(); ++t) {
    for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
      const auto local = to_psurface_local<ctype>(m.node_position[n]);
      const int where = m.node_location[n];
      const int target = m.node_target[n];
      int idx = -1;
      switch (m.node_type[n]) {
        case NodeType::corner: idx = factory.addCornerNode(t, where, target); break;
        case NodeType::ghost:
          idx = factory.addGhostNode(t, where, m.node_image_element[n],
                                     to_psurface_local<ctype>(m.node_image_local[n]));
          ++out.ghost_nodes;
          break;
        case NodeType::touching: idx = factory.addTouchingNode(t, local, where, target); break;
        case NodeType::interior: idx = factory.addInteriorNode(t, local, target); break;
        case NodeType::rim_on_edge:
        case NodeType::rim_inside: continue;  // refused above
        case NodeType::intersection: {
          ++out.intersection_nodes;
          if (local_index[std::size_t(n)] >= 0) continue;  // entered with its partner
          const WorldPoint<2> image = map.node_target_world(n);
          const V3 range(ctype(image(0)), ctype(image(1)), ctype(image(2)));
          const Index other = partner[std::size_t(n)];
          if (other == invalid_index) {
            // Boundary edge: PSurface's factory has no single intersection node; enter it as
            // addIntersectionNodePair would, on one triangle.
            ps.iPos.push_back(range);
            auto& nodes = ps.triangles(t).nodes;
            nodes.emplace_back();
            nodes.back().setValue(local, int(ps.iPos.size() - 1),
                                  psurface::Node<ctype>::INTERSECTION_NODE);
            nodes.back().setDomainEdge(where);
            idx = int(nodes.size() - 1);
          } else {
            const Index t2 = map.node_element(other);
            const psurface::NodeBundle pair = factory.addIntersectionNodePair(
                t, t2, local, to_psurface_local<ctype>(m.node_position[other]), where,
                m.node_location[other], range);
            idx = pair[0].idx;
            local_index[std::size_t(other)] = pair[1].idx;
          }
          break;
        }
      }
      local_index[std::size_t(n)] = idx;
    }
  }
  for (Index t = 0; t < s1.element_count(); ++t) {
    auto& tri = ps.triangles(t);
    for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n)
      for (Index i = m.neighbor_begin[n]; i < m.neighbor_begin[n + 1]; ++i) {
        const Index other = m.neighbor[i];
        if (other < n) continue;
        tri.addEdge(local_index[std::size_t(n)], local_index[std::size_t(other)],
                    m.neighbor_edge_kind[i] == GraphEdgeKind::closure);
      }
    for (int k = 0; k < 3; ++k) {
      const auto nodes = map.edge_nodes(t, k);
      tri.edgePoints[k].resize(nodes.size());
      for (std::size_t j = 0; j < nodes.size(); ++j)
        tri.edgePoints[k][j] = local_index[std::size_t(nodes[j])];
    }
  }
  // The graph is already triangulated (plmap's closure), so PSurface's own closure step
  // (insertExtraEdges) is skipped: it assumes one fixed triangulation of the quadrangles at
  // intersection nodes and would add edges crossing plmap's closure. What remains of
  // PSurface::createPointLocationStructure() is the per-triangle set-up below.
  out.edges_before_closure = count_graph_edges(ps);
  {
    peers::QuietStdout quiet;  // PSurface prints a line for every query it cannot map
    for (Index t = 0; t < s1.element_count(); ++t) ps.triangles(t).createPointLocationStructure();
  }
  ps.hasUpToDatePointLocationStructure = true;
  const std::size_t heap3 = heap_in_use();
  out.build_seconds = peers::process_cpu_seconds() - t0;

  // For the record: PSurface's full set-up, closure step included, on a copy (after the heap
  // was measured).
  out.own_closure = std::make_unique<psurface::PSurface<2, ctype>>(ps);
  {
    peers::QuietStdout quiet;
    out.own_closure->createPointLocationStructure();
  }
  out.edges_added_by_psurface = count_graph_edges(*out.own_closure) - out.edges_before_closure;

  out.target_heap_bytes = heap1 - heap0;
  out.domain_heap_bytes = heap2 - heap1;
  out.graph_heap_bytes = heap3 - heap2;
  out.nodes = std::size_t(ps.getNumNodes());
  std::size_t payload = ps.iPos.size() * sizeof(V3);
  for (std::size_t t = 0; t < ps.getNumTriangles(); ++t) {
    const auto& tri = ps.triangles(int(t));
    payload += tri.nodes.size() * sizeof(psurface::Node<ctype>);
    for (const auto& node : tri.nodes) payload += node.nbs.size() * sizeof(node.nbs[0]);
    for (int k = 0; k < 3; ++k) payload += tri.edgePoints[k].size() * sizeof(psurface::NodeIdx);
  }
  out.graph_payload_bytes = payload;
  return out;
}

// ---- one case ----------------------------------------------------------------------------------

/// How PSurface's images compare with plmap's (relative to S2's bounding-box diagonal).
/// PSurface's image is c0 P(v0) + c1 P(v1) + (1 - c0 - c1) P(v2).
struct Agreement {
  std::size_t compared = 0, failed = 0, invalid_vertex = 0, within_1e9 = 0, within_1e6 = 0,
              within_1e3 = 0;
  /// Wrong answers (an invalid vertex or off by more than 1e-6), by where the query lies, in
  /// this order: in PSurface's edge strips (within 0.001 of an element edge in local
  /// coordinates, where map() evaluates at the projection onto the edge with single-precision
  /// S2 positions); else in a plmap region with a ghost-node corner; else in a region with two
  /// or three intersection-node corners (where getActualVertices() follows S2 edges across S1
  /// edges); else anywhere.
  std::size_t wrong_in_edge_strip = 0, wrong_at_ghost_region = 0,
              wrong_at_intersection_region = 0, wrong_elsewhere = 0;

  void count_wrong(bool edge_strip, bool ghost_region, bool intersection_region) {
    if (edge_strip) ++wrong_in_edge_strip;
    else if (ghost_region) ++wrong_at_ghost_region;
    else if (intersection_region) ++wrong_at_intersection_region;
    else ++wrong_elsewhere;
  }
  double max_distance = 0;

  Json json() const {
    const double n = double(std::max<std::size_t>(compared, 1));
    return {{"compared", compared},
            {"failed", failed},
            {"invalid_vertex", invalid_vertex},
            {"agree_1e-9", double(within_1e9) / n},
            {"agree_1e-6", double(within_1e6) / n},
            {"agree_1e-3", double(within_1e3) / n},
            {"max_relative_distance", max_distance},
            {"wrong_in_edge_strip", wrong_in_edge_strip},
            {"wrong_at_ghost_region", wrong_at_ghost_region},
            {"wrong_at_intersection_region", wrong_at_intersection_region},
            {"wrong_elsewhere", wrong_elsewhere}};
  }
};

template <class ctype>
Agreement compare_images(const psurface::PSurface<2, ctype>& ps, const PlMap<2>& map,
                         const std::vector<SurfacePoint<2>>& queries,
                         const std::vector<Evaluation<2>>& reference, std::size_t count) {
  const auto& s2 = map.target();
  const double diagonal = (s2.bounding_box_max() - s2.bounding_box_min()).norm();
  Agreement a;
  peers::QuietStdout quiet;
  std::tr1::array<int, 3> v;
  psurface::StaticVector<ctype, 2> c;
  for (std::size_t i = 0; i < std::min(count, queries.size()); ++i) {
    if (!reference[i].in_domain) continue;
    ++a.compared;
    if (!ps.map(queries[i].element, to_psurface_local<ctype>(queries[i].local), v, c)) {
      ++a.failed;
      continue;
    }
    const auto& region = map.data().region_corners[reference[i].region];
    const bool ghost_region = std::any_of(region.begin(), region.end(), [&](Index n) {
      return map.data().node_type[n] == NodeType::ghost;
    });
    const bool intersection_region =
        !ghost_region && std::count_if(region.begin(), region.end(), [&](Index n) {
          return map.data().node_type[n] == NodeType::intersection;
        }) >= 2;
    const auto& x = queries[i].local;
    const bool edge_strip = x(0) < 0.001 || x(1) < 0.001 || 1 - x(0) - x(1) < 0.001;
    if (std::any_of(v.begin(), v.end(), [&](int x) { return x < 0 || x >= s2.vertex_count(); })) {
      ++a.invalid_vertex;
      a.count_wrong(edge_strip, ghost_region, intersection_region);
      continue;
    }
    const WorldPoint<2> image = double(c[0]) * s2.vertex(v[0]) + double(c[1]) * s2.vertex(v[1]) +
                                (1 - double(c[0]) - double(c[1])) * s2.vertex(v[2]);
    const double distance = (image - reference[i].world).norm() / diagonal;
    a.max_distance = std::max(a.max_distance, distance);
    a.within_1e9 += distance <= 1e-9;
    a.within_1e6 += distance <= 1e-6;
    a.within_1e3 += distance <= 1e-3;
    // NaN (PSurface's barycentric coordinates on a degenerate vertex triple) counts as wrong.
    if (!(distance <= 1e-6)) a.count_wrong(edge_strip, ghost_region, intersection_region);
  }
  return a;
}

template <class ctype>
Json measure_psurface(const PSurfaceMap<ctype>& psm, const PlMap<2>& map,
                      const std::vector<SurfacePoint<2>>& queries,
                      const std::vector<Evaluation<2>>& reference, const std::string& label) {
  const auto& ps = *psm.psurface;
  std::vector<psurface::StaticVector<ctype, 2>> local(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) local[i] = to_psurface_local<ctype>(queries[i].local);
  // The answers are stored as plmap's evaluate_batch stores its own.
  std::vector<std::tr1::array<int, 3>> vertices(queries.size());
  std::vector<psurface::StaticVector<ctype, 2>> coords(queries.size());
  std::vector<char> ok(queries.size());
  double seconds = 0;
  {
    peers::QuietStdout quiet;
    seconds = median_cpu_seconds([&] {
      for (std::size_t i = 0; i < queries.size(); ++i)
        ok[i] = ps.map(queries[i].element, local[i], vertices[i], coords[i]);
    });
  }
  Json result = {{"label", label},
                 {"evals_per_cpu_s", double(queries.size()) / seconds},
                 {"cpu_seconds", seconds},
                 {"nodes", psm.nodes},
                 {"ghost_nodes", psm.ghost_nodes},
                 {"intersection_nodes", psm.intersection_nodes},
                 {"edges_before_closure", psm.edges_before_closure},
                 {"edges_added_by_psurface", psm.edges_added_by_psurface},
                 {"graph_heap_bytes", psm.graph_heap_bytes},
                 {"graph_heap_bytes_per_node", double(psm.graph_heap_bytes) / double(psm.nodes)},
                 {"graph_payload_bytes_per_node", double(psm.graph_payload_bytes) / double(psm.nodes)},
                 {"domain_heap_bytes", psm.domain_heap_bytes},
                 {"target_heap_bytes", psm.target_heap_bytes},
                 {"build_cpu_seconds", psm.build_seconds}};
  result["agreement"] = compare_images(ps, map, queries, reference, queries.size()).json();
  result["agreement_own_closure"] =
      compare_images(*psm.own_closure, map, queries, reference, queries.size()).json();
  return result;
}

/// PSurface<2,double>::map(), plmap's cell-grid locator and the region-known floor, timed in
/// turns on one query stream: round r runs the three one after the other, in an order that
/// rotates with r, so a slow spell of the shared machine falls on every one of them alike.
/// Reported per contender: the best round (the least disturbed pass) and, per round, plmap's
/// rate over the other two measured seconds apart; the median of those ratios is the figure
/// least moved by load that drifts between the phases of a run.
Json interleaved_rates(const PSurfaceMap<double>& psm, const PlMap<2>& map,
                       const std::vector<SurfacePoint<2>>& queries,
                       const std::vector<Evaluation<2>>& reference, int rounds) {
  const auto& ps = *psm.psurface;
  std::vector<psurface::StaticVector<double, 2>> local(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) local[i] = to_psurface_local<double>(queries[i].local);
  std::vector<std::tr1::array<int, 3>> vertices(queries.size());
  std::vector<psurface::StaticVector<double, 2>> coords(queries.size());
  std::vector<char> ok(queries.size());
  std::vector<Evaluation<2>> out(queries.size());
  // The floor evaluates the in-domain queries in their known region; the other two are timed
  // on the same subset so that the three do the same number of evaluations.
  std::vector<std::size_t> inside;
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (reference[i].in_domain) inside.push_back(i);
  std::vector<SurfacePoint<2>> inside_queries;
  for (const std::size_t i : inside) inside_queries.push_back(queries[i]);
  std::vector<Evaluation<2>> inside_out(inside.size());

  std::array<std::vector<double>, 3> seconds;  // psurface, cell-grid, floor
  with_point_locator<2>("cell-grid", [&](auto& locator) {
    prepare_point_locator<2>(locator, map);
    const std::array<std::function<void()>, 3> work = {
        [&] {
          peers::QuietStdout quiet;
          for (const std::size_t i : inside) ok[i] = ps.map(queries[i].element, local[i], vertices[i], coords[i]);
        },
        [&] { evaluate_batch<2>(map, inside_queries, inside_out, locator, 1); },
        [&] {
          for (const std::size_t i : inside)
            out[i] = evaluate_in_region(map, reference[i].region, queries[i].local);
        }};
    for (int r = 0; r < rounds; ++r)
      for (int k = 0; k < 3; ++k) {
        const int who = (r + k) % 3;
        const double t0 = peers::process_cpu_seconds();
        work[who]();
        seconds[who].push_back(peers::process_cpu_seconds() - t0);
      }
  });
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  std::vector<double> over_psurface, over_floor;
  for (int r = 0; r < rounds; ++r) {
    over_psurface.push_back(seconds[0][r] / seconds[1][r]);
    over_floor.push_back(seconds[1][r] / seconds[2][r]);
  }
  const double n = double(inside.size());
  auto best = [&](int who) { return n / *std::min_element(seconds[who].begin(), seconds[who].end()); };
  return {{"rounds", rounds},
          {"evaluations_per_round", inside.size()},
          {"psurface_double_best_evals_per_cpu_s", best(0)},
          {"cell_grid_best_evals_per_cpu_s", best(1)},
          {"floor_best_evals_per_cpu_s", best(2)},
          {"cell_grid_over_psurface_median_of_rounds", median(over_psurface)},
          {"cell_grid_over_psurface_min_of_rounds", *std::min_element(over_psurface.begin(), over_psurface.end())},
          {"cell_grid_over_psurface_max_of_rounds", *std::max_element(over_psurface.begin(), over_psurface.end())},
          {"cell_grid_time_over_floor_median_of_rounds", median(over_floor)},
          {"cell_grid_time_over_floor_max_of_rounds", *std::max_element(over_floor.begin(), over_floor.end())}};
}

Json run_case(const Case& c, std::size_t query_count, int rounds) {
  const PlMap<2>& map = *c.map;
  const auto queries = bench::random_queries(map.domain(), query_count, 12345);
  std::vector<Evaluation<2>> out(queries.size()), reference(queries.size());
  // Reference images by brute force (not timed).
  with_point_locator<2>("brute-force", [&](auto& locator) {
    evaluate_batch<2>(map, queries, reference, locator, 0);
  });
  std::size_t outside = 0;
  for (const auto& e : reference) outside += !e.in_domain;

  Json result = {{"case", c.name},
                 {"elements", map.domain().element_count()},
                 {"target_elements", map.target().element_count()},
                 {"nodes", map.node_count()},
                 {"regions", map.region_count()},
                 {"queries", queries.size()},
                 {"queries_outside_domain", outside},
                 {"plmap_memory_bytes", map.memory_bytes()},
                 {"plmap_bytes_per_node", double(map.memory_bytes()) / map.node_count()},
                 {"plmap_bytes_per_region", double(map.memory_bytes()) / map.region_count()}};
  {
    // memory_bytes() counts the capacity of what the map stores; by size, the stored per-node
    // arrays and the stored per-region arrays, both per node; then every array by size, the
    // derived graph arrays included (data() derives them here, after memory_bytes() was read).
    const auto& s = map.stored();
    auto b = [](const auto& v) { return double(v.size() * sizeof(v[0])); };
    const double nodes = b(s.node_begin) + b(s.node_position) + b(s.node_type) + b(s.node_location) +
                         b(s.node_image_element) + b(s.node_image_local) + b(s.node_target);
    const double regions = b(s.region_begin) + b(s.region_corners) + b(s.region_target) + b(s.region_map) +
                           b(s.start_region);
    result["plmap_graph_size_bytes_per_node"] = nodes / map.node_count();
    result["plmap_region_size_bytes_per_node"] = regions / map.node_count();
    result["plmap_elements_with_stored_graph"] = map.elements_with_stored_graph();
    const auto& m = map.data();
    result["plmap_derived_bytes_per_node"] = double(map.derived_bytes()) / map.node_count();
    Json arrays = Json::array();
    auto add = [&](const char* name, const auto& v) {
      arrays.push_back({{"array", name}, {"bytes_per_node", b(v) / map.node_count()}});
    };
    add("node_begin", m.node_begin);
    add("node_position", m.node_position);
    add("node_type", m.node_type);
    add("node_location", m.node_location);
    add("node_image_element", m.node_image_element);
    add("node_image_local", m.node_image_local);
    add("node_target", m.node_target);
    add("neighbor_begin", m.neighbor_begin);
    add("neighbor", m.neighbor);
    add("neighbor_edge_kind", m.neighbor_edge_kind);
    add("edge_node_begin", m.edge_node_begin);
    add("edge_node", m.edge_node);
    add("region_begin", m.region_begin);
    add("region_corners", m.region_corners);
    add("region_neighbors", m.region_neighbors);
    add("region_target", m.region_target);
    add("region_map", m.region_map);
    add("start_region", m.start_region);
    result["plmap_arrays"] = arrays;
    // What storing less costs: the constructor's check that the graph follows from the regions
    // (it derives every element's graph once), and deriving it again on demand (data()).
    const MapData<2> full = m;
    double check_seconds = 0, derive_seconds = 0;
    check_seconds = median_cpu_seconds([&] { PlMap<2> again(map.domain_ptr(), map.target_ptr(), full); });
    derive_seconds = median_cpu_seconds([&] {
      PlMap<2> again(map.domain_ptr(), map.target_ptr(), full);
      again.data();
    }) - check_seconds;
    result["plmap_construct_ns_per_node"] = 1e9 * check_seconds / map.node_count();
    result["plmap_derive_graph_ns_per_node"] = 1e9 * derive_seconds / map.node_count();
  }
  for (const auto name : point_locator_names<2>()) {
    double seconds = 0;
    with_point_locator<2>(name, [&](auto& locator) {
      prepare_point_locator<2>(locator, map);  // table-based locators: set-up is not query time
      seconds = median_cpu_seconds([&] { evaluate_batch<2>(map, queries, out, locator, 1); });
    });
    std::size_t differ = 0;
    for (std::size_t i = 0; i < queries.size(); ++i)
      differ += out[i].in_domain != reference[i].in_domain ||
                (out[i].in_domain && (out[i].world - reference[i].world).norm() >
                                         1e-9 * map.target().max_edge_length());
    result["plmap"][std::string(name)] = {{"evals_per_cpu_s", double(queries.size()) / seconds},
                                          {"cpu_seconds", seconds},
                                          {"differs_from_brute_force", differ}};
  }
  {
    auto psm = build_psurface<double>(map);
    result["psurface"].push_back(measure_psurface(psm, map, queries, reference, "PSurface<2,double>"));
    if (rounds > 0) result["interleaved"] = interleaved_rates(psm, map, queries, reference, rounds);
  }
  {
    auto psm = build_psurface<float>(map);
    result["psurface"].push_back(measure_psurface(psm, map, queries, reference, "PSurface<2,float>"));
  }
  return result;
}

void print_markdown(const Json& report) {
  fmt::print("| map | nodes | regions | library / locator | Meval/CPU-s | ratio plmap/PSurface<double> "
             "| ratio plmap/PSurface<float> |\n|---|---:|---:|---|---:|---:|---:|\n");
  for (const auto& r : report["cases"]) {
    const double ps_double = r["psurface"][0]["evals_per_cpu_s"].get<double>();
    const double ps_float = r["psurface"][1]["evals_per_cpu_s"].get<double>();
    bool first = true;
    auto row = [&](const std::string& who, double rate, bool ratio) {
      fmt::print("| {} | {} | {} | {} | {:.3f} | {} | {} |\n", first ? r["case"].get<std::string>() : "",
                 first ? std::to_string(r["nodes"].get<long>()) : "",
                 first ? std::to_string(r["regions"].get<long>()) : "", who, rate / 1e6,
                 ratio ? fmt::format("{:.1f}", rate / ps_double) : "",
                 ratio ? fmt::format("{:.1f}", rate / ps_float) : "");
      first = false;
    };
    for (const auto& p : r["psurface"]) row(p["label"].get<std::string>() + "::map()", p["evals_per_cpu_s"], false);
    for (const auto& [name, l] : r["plmap"].items()) row("plmap " + name, l["evals_per_cpu_s"], true);
  }

  if (report["cases"][0].contains("interleaved")) {
    fmt::print("\n| map | rounds | best Meval/CPU-s: PSurface<double> / cell-grid / floor | cell-grid / "
               "PSurface<double>, per round: median (min–max) | cell-grid time / floor, per round: "
               "median (max) |\n|---|---:|---|---|---|\n");
    for (const auto& r : report["cases"]) {
      const auto& i = r["interleaved"];
      fmt::print("| {} | {} | {:.3f} / {:.3f} / {:.3f} | {:.1f} ({:.1f}–{:.1f}) | {:.2f} ({:.2f}) |\n",
                 r["case"].get<std::string>(), i["rounds"].get<int>(),
                 i["psurface_double_best_evals_per_cpu_s"].get<double>() / 1e6,
                 i["cell_grid_best_evals_per_cpu_s"].get<double>() / 1e6,
                 i["floor_best_evals_per_cpu_s"].get<double>() / 1e6,
                 i["cell_grid_over_psurface_median_of_rounds"].get<double>(),
                 i["cell_grid_over_psurface_min_of_rounds"].get<double>(),
                 i["cell_grid_over_psurface_max_of_rounds"].get<double>(),
                 i["cell_grid_time_over_floor_median_of_rounds"].get<double>(),
                 i["cell_grid_time_over_floor_max_of_rounds"].get<double>());
    }
  }

  fmt::print("\n| map | library | PSurface closure | compared | agree 1e-9 | agree 1e-6 | agree 1e-3 | "
             "map() failed | invalid vertex | wrong: edge strip / ghost region / 2-3 intersection "
             "corners / elsewhere | ghost / intersection nodes | closure edges PSurface added |\n"
             "|---|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|\n");
  for (const auto& r : report["cases"])
    for (const auto& p : r["psurface"])
      for (const auto* which : {"agreement", "agreement_own_closure"}) {
        const auto& a = p[which];
        const bool own = std::string(which) == "agreement_own_closure";
        fmt::print("| {} | {} | {} | {} | {:.4f} | {:.4f} | {:.4f} | {} | {} | {} / {} / {} / {} | {} / {} | {} |\n",
                   r["case"].get<std::string>(), p["label"].get<std::string>(),
                   own ? "insertExtraEdges" : "plmap's", a["compared"].get<long>(),
                   a["agree_1e-9"].get<double>(), a["agree_1e-6"].get<double>(),
                   a["agree_1e-3"].get<double>(), a["failed"].get<long>(),
                   a["invalid_vertex"].get<long>(), a["wrong_in_edge_strip"].get<long>(),
                   a["wrong_at_ghost_region"].get<long>(), a["wrong_at_intersection_region"].get<long>(),
                   a["wrong_elsewhere"].get<long>(),
                   p["ghost_nodes"].get<long>(),
                   p["intersection_nodes"].get<long>(),
                   own ? std::to_string(p["edges_added_by_psurface"].get<long>()) : "0");
      }

  fmt::print("\n| map | nodes (plmap / PSurface) | plmap memory_bytes()/node | by size: plmap graph + "
             "region arrays per node | PSurface<double> heap/node | PSurface<float> heap/node | by size: "
             "PSurface<double> / <float> per node | ratio plmap/PSurface<double> | ratio plmap/PSurface<float> |\n"
             "|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& r : report["cases"]) {
    const double plmap_per_node = r["plmap_bytes_per_node"].get<double>();
    const auto& pd = r["psurface"][0];
    const auto& pf = r["psurface"][1];
    fmt::print("| {} | {} / {} | {:.1f} | {:.1f} + {:.1f} | {:.1f} | {:.1f} | {:.1f} / {:.1f} | {:.2f} | {:.2f} |\n",
               r["case"].get<std::string>(), r["nodes"].get<long>(), pd["nodes"].get<long>(), plmap_per_node,
               r["plmap_graph_size_bytes_per_node"].get<double>(),
               r["plmap_region_size_bytes_per_node"].get<double>(),
               pd["graph_heap_bytes_per_node"].get<double>(), pf["graph_heap_bytes_per_node"].get<double>(),
               pd["graph_payload_bytes_per_node"].get<double>(), pf["graph_payload_bytes_per_node"].get<double>(),
               plmap_per_node / pd["graph_heap_bytes_per_node"].get<double>(),
               plmap_per_node / pf["graph_heap_bytes_per_node"].get<double>());
  }

  // Every array of the map by size, in bytes per node; the graph arrays are derived on demand
  // (PlMap::data()), except on the elements counted in the last row.
  fmt::print("\n| array |");
  for (const auto& r : report["cases"]) fmt::print(" {} |", r["case"].get<std::string>());
  fmt::print("\n|---|");
  for (std::size_t i = 0; i < report["cases"].size(); ++i) fmt::print("---:|");
  fmt::print("\n");
  const auto& first = report["cases"][0]["plmap_arrays"];
  for (std::size_t a = 0; a < first.size(); ++a) {
    fmt::print("| {} |", first[a]["array"].get<std::string>());
    for (const auto& r : report["cases"]) fmt::print(" {:.2f} |", r["plmap_arrays"][a]["bytes_per_node"].get<double>());
    fmt::print("\n");
  }
  fmt::print("| derived on demand (derived_bytes()) |");
  for (const auto& r : report["cases"]) fmt::print(" {:.2f} |", r["plmap_derived_bytes_per_node"].get<double>());
  fmt::print("\n| constructing from the full arrays, ns per node |");
  for (const auto& r : report["cases"]) fmt::print(" {:.0f} |", r["plmap_construct_ns_per_node"].get<double>());
  fmt::print("\n| deriving the graph arrays (data()), ns per node |");
  for (const auto& r : report["cases"]) fmt::print(" {:.0f} |", r["plmap_derive_graph_ns_per_node"].get<double>());
  fmt::print("\n| elements that store their graph |");
  for (const auto& r : report["cases"]) fmt::print(" {} of {} |", r["plmap_elements_with_stored_graph"].get<long>(), r["elements"].get<long>());
  fmt::print("\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t query_count = 1 << 19;
  std::string femur_path, json_path;
  std::vector<std::string> map_paths;
  bool sphere = true;
  int rounds = 9;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--queries" && i + 1 < argc) query_count = std::stoul(argv[++i]);
    else if (a == "--femur" && i + 1 < argc) femur_path = argv[++i];
    else if (a == "--map" && i + 1 < argc) map_paths.emplace_back(argv[++i]);
    else if (a == "--json" && i + 1 < argc) json_path = argv[++i];
    else if (a == "--no-sphere") sphere = false;
    else if (a == "--rounds" && i + 1 < argc) rounds = std::stoi(argv[++i]);
    else {
      fmt::print(stderr, "usage: {} [--femur femur.off] [--map file.plmap]... [--no-sphere] "
                 "[--queries N] [--rounds R] [--json out.json]\n", argv[0]);
      return 2;
    }
  }
  try {
    std::vector<Case> cases;
    if (!femur_path.empty()) {
      const auto femur = bench::coarse_femur(femur_path, 500);
      for (int k : {4, 5})
        cases.push_back({fmt::format("femur {} tris, {}x{} refinement", femur->element_count(), k, k),
                         generators::subdivision_map(femur, k, 0.2, 200 + k).map});
    }
    if (sphere) {
      // Two spheres, the outer one rotated so that the meshes do not match: S2 projected onto
      // S1 along S1's vertex normals, a map with ghost and intersection nodes.
      auto s1 = test::sphere(4, 1.0);
      auto s2 = test::sphere(4, 1.1, false, 0.3);
      auto projected = project<2>(s1, s2);
      cases.push_back({fmt::format("sphere {} -> sphere {} tris, projection", s1->element_count(),
                                   s2->element_count()),
                       std::make_shared<const PlMap<2>>(std::move(projected.map))});
    }
    for (const auto& path : map_paths)
      cases.push_back({std::filesystem::path(path).filename().string(),
                       std::make_shared<const PlMap<2>>(load_map<2>(path))});

    if (cases.empty()) {
      fmt::print(stderr, "psurface_eval: no map to measure (give --femur, --map, or drop --no-sphere)\n");
      return 2;
    }
    Json report;
    report["queries"] = query_count;
    for (const auto& c : cases) {
      fmt::print(stderr, "measuring {} ...\n", c.name);
      report["cases"].push_back(run_case(c, query_count, rounds));
    }
    print_markdown(report);
    if (!json_path.empty()) std::ofstream(json_path) << report.dump(2) << "\n";
  } catch (const std::exception& e) {
    fmt::print(stderr, "psurface_eval: {}\n", e.what());
    return 1;
  }
  return 0;
}
