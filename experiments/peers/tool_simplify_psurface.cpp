// PSurface 2.0's simplification with a parametrization (Debian libpsurface-dev) as one tool of
// the simplification benchmark. The library exports the steps (ParamToolBox's point removal,
// Triangulator's error estimate of a removal, VertexHeap, PSurfaceSmoother's edge relaxation) but
// no driver; the driver here orders the vertices by PSurface's own error estimate in its
// VertexHeap and removes the cheapest until the target, as PSurface's psurface-simplify program
// does, and then relaxes the parametrization across every base edge once per sweep.
//
// The result is measured with plmap's code: the condition number of every region of PSurface's
// (closed) plane graphs, from the world triangle of its three nodes on the base grid and their
// image positions (verify's triangle_conditioning); the largest node-to-image distance (the same
// modified Hausdorff distance plmap reports); the aspect ratio of the base grid and of its uniform
// refinement moved through PSurface::positionMap.

#include "simplification_tools.hpp"

#include <plmap/construct/refine_through_map.hpp>
#include <plmap/verify/quality.hpp>

// PSurface's headers are not self-contained: this order compiles.
#define PSURFACE_STANDALONE
// clang-format off
#include <psurface/PSurface.h>
#include <psurface/Box.h>
#include <psurface/MultiDimOctree.h>
#include <psurface/EdgeIntersectionFunctor.h>
#include <psurface/VertexHeap.h>
#include <psurface/QualityRequest.h>
#include <psurface/HxParamToolBox.h>
#include <psurface/Triangulator.h>
#include <psurface/PSurfaceSmoother.h>
#include <psurface/GmshIO.h>
// clang-format on

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>

namespace plmap::peers {

namespace {

using Par = psurface::PSurface<2, float>;
using EdgeTree = psurface::MultiDimOctree<psurface::Edge, psurface::EdgeIntersectionFunctor, float, 3>;
namespace toolbox = psurface::ParamToolBox;

/// PSurface reads an identity parametrization from a Gmsh 2 file (GmshIO::readGmsh); this is
/// the fine mesh in that format, in a temporary file removed when the object dies.
class GmshFile {
 public:
  explicit GmshFile(const Surface<2>& mesh) {
    char name[] = "/tmp/plmap-psurface-XXXXXX";
    const int fd = mkstemp(name);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for PSurface's input");
    close(fd);
    path_ = name;
    std::FILE* f = std::fopen(path_.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path_);
    std::fprintf(f, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%zu\n", mesh.vertices().size());
    for (std::size_t i = 0; i < mesh.vertices().size(); ++i) {
      const auto& p = mesh.vertices()[i];
      std::fprintf(f, "%zu %.17g %.17g %.17g\n", i + 1, p(0), p(1), p(2));
    }
    std::fprintf(f, "$EndNodes\n$Elements\n%zu\n", mesh.elements().size());
    for (std::size_t i = 0; i < mesh.elements().size(); ++i) {
      const auto& t = mesh.elements()[i];
      std::fprintf(f, "%zu 2 0 %lld %lld %lld\n", i + 1, static_cast<long long>(t[0]) + 1,
                   static_cast<long long>(t[1]) + 1, static_cast<long long>(t[2]) + 1);
    }
    std::fprintf(f, "$EndElements\n");
    std::fclose(f);
  }
  ~GmshFile() { std::remove(path_.c_str()); }
  GmshFile(const GmshFile&) = delete;
  GmshFile& operator=(const GmshFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// PSurface's estimate of what removing vertex v costs (blocked: it cannot be removed): a
/// regular vertex is judged on its full star, a vertex on a feature line on each half star.
VertexHeap::ErrorValue removal_cost(Par* par, int v, const psurface::QualityRequest& quality, EdgeTree& tree) {
  VertexHeap::ErrorValue cost;
  int feature_a = -1, feature_b = -1;
  const int status = toolbox::computeFeatureStatus(par, v, feature_a, feature_b);
  if (status == toolbox::FEATURE_POINT || par->vertices(v).degree() < 3) {
    cost.block();
    return cost;
  }
  std::vector<std::vector<int>> half_vertices, half_triangles;
  std::vector<int> patches;
  if (status == toolbox::REGULAR_POINT) {
    feature_a = par->vertices(v).edges[0];
    feature_b = par->vertices(v).edges[1];
  }
  if (!toolbox::findAllHalfStars(v, feature_a, feature_b, half_vertices, half_triangles, patches, par)) {
    cost.block();
    return cost;
  }
  if (status == toolbox::REGULAR_POINT) {
    std::vector<int> star_vertices, star_triangles;
    toolbox::makeFullStarOutOfHalfStars(half_vertices[0], half_triangles[0], half_vertices[1], half_triangles[1],
                                        star_vertices, star_triangles);
    psurface::Triangulator::estimateStarError(star_vertices, v, quality, star_triangles, cost, tree, par);
    cost.value /= 2;  // per half star, as for feature-line vertices
    return cost;
  }
  double sum = 0.0;
  for (std::size_t h = 0; h < half_vertices.size(); ++h) {
    if (half_triangles[h].size() < 2) continue;
    VertexHeap::ErrorValue part;
    psurface::Triangulator::estimateHalfStarError(half_vertices[h], v, quality, half_triangles[h], part, tree, par);
    if (part.isBlocked()) {
      cost.block();
      return cost;
    }
    sum += part.value;
  }
  cost.value = static_cast<float>(sum / double(half_vertices.size()));
  return cost;
}

bool remove_vertex(Par* par, int v, const psurface::QualityRequest& quality, EdgeTree* tree) {
  int feature_a = -1, feature_b = -1;
  const int status = toolbox::computeFeatureStatus(par, v, feature_a, feature_b);
  if (status == toolbox::FEATURE_POINT) return false;
  if (status == toolbox::REGULAR_POINT) return toolbox::removeRegularPoint(par, v, quality, tree);
  return toolbox::removeFeatureLinePoint(par, v, quality, status, feature_a, feature_b, tree);
}

std::size_t live_triangles(const Par& par) { return par.getNumTriangles() - par.freeTriangleStack.size(); }

WorldPoint<2> world(const psurface::StaticVector<float, 3>& p) { return {double(p[0]), double(p[1]), double(p[2])}; }

/// The base-grid position of a point with PSurface's local coordinates (lambda0, lambda1) on
/// base triangle t (corner 0 at (1, 0), corner 1 at (0, 1), corner 2 at (0, 0)).
WorldPoint<2> base_position(const Par& par, int t, double l0, double l1) {
  const auto& tri = par.triangles(t);
  return l0 * world(par.vertices(tri.vertices[0])) + l1 * world(par.vertices(tri.vertices[1])) +
         (1.0 - l0 - l1) * world(par.vertices(tri.vertices[2]));
}

struct GraphFigures {
  std::vector<double> kappas;
  double hausdorff = 0.0;
  long nodes = 0;
  /// Sum of the regions' areas on the base grid over the base grid's area: 1 when the regions
  /// enumerated tile every base triangle (a check of the enumeration, not of PSurface).
  double region_area_ratio = 0.0;
};

double area(const std::array<WorldPoint<2>, 3>& t) { return 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm(); }

/// Regions (the triangles of every base triangle's closed plane graph) and nodes of the map.
GraphFigures measure_graph(const Par& par) {
  GraphFigures g;
  double region_area = 0.0, base_area = 0.0;
  for (int t = 0; t < int(par.getNumTriangles()); ++t) {
    const auto& tri = par.triangles(t);
    base_area += area({base_position(par, t, 1, 0), base_position(par, t, 0, 1), base_position(par, t, 0, 0)});
    g.nodes += long(tri.nodes.size());
    for (std::size_t n = 0; n < tri.nodes.size(); ++n) {
      const auto& xi = tri.nodes[n].domainPos();
      const WorldPoint<2> p = base_position(par, t, xi[0], xi[1]);
      g.hausdorff = std::max(g.hausdorff, (p - world(par.imagePos(t, psurface::NodeIdx(n)))).norm());
    }
    for (auto it = tri.firstTriangle(); it.isValid(); ++it) {
      std::array<WorldPoint<2>, 3> domain, image;
      for (int k = 0; k < 3; ++k) {
        const auto node = it.vertices(k);
        const auto& xi = tri.nodes[node].domainPos();
        domain[k] = base_position(par, t, xi[0], xi[1]);
        image[k] = world(par.imagePos(t, node));
      }
      g.kappas.push_back(triangle_conditioning(domain, image).kappa);
      region_area += area(domain);
    }
  }
  g.region_area_ratio = base_area > 0 ? region_area / base_area : 0.0;
  return g;
}

Surface<2> base_grid(const Par& par) {
  std::vector<WorldPoint<2>> vertices;
  for (int v = 0; v < int(par.getNumVertices()); ++v) vertices.push_back(world(par.vertices(v)));
  std::vector<ElementCorners<2>> triangles;
  for (int t = 0; t < int(par.getNumTriangles()); ++t) {
    const auto& tri = par.triangles(t);
    triangles.push_back({Index(tri.vertices[0]), Index(tri.vertices[1]), Index(tri.vertices[2])});
  }
  return Surface<2>(std::move(vertices), std::move(triangles));
}

/// Every base triangle cut into 4^levels triangles on its barycentric lattice, every lattice point
/// moved to its image by PSurface::positionMap (as plmap's refine_through_map does with Ξ). The
/// triangles keep their own copies of shared lattice points: only their shapes are measured.
Surface<2> refined_through_map(const Par& par, int levels, long& failures) {
  const int n = 1 << levels;
  std::vector<WorldPoint<2>> vertices;
  std::vector<ElementCorners<2>> triangles;
  for (int t = 0; t < int(par.getNumTriangles()); ++t) {
    std::vector<Index> lattice;  // (i, j) with i + j <= n, row by row
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        psurface::StaticVector<float, 2> xi(float(double(i) / n), float(double(j) / n));
        psurface::StaticVector<float, 3> p;
        if (!par.positionMap(t, xi, p)) {
          ++failures;
          vertices.push_back(base_position(par, t, double(i) / n, double(j) / n));
        } else {
          vertices.push_back(world(p));
        }
        lattice.push_back(Index(vertices.size() - 1));
      }
    const auto at = [&](int i, int j) { return lattice[std::size_t(i * (n + 1) - i * (i - 1) / 2 + j)]; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return Surface<2>(std::move(vertices), std::move(triangles));
}

}  // namespace

SimplificationOutcome simplify_with_psurface(const SimplificationRequest& request, Measurement& clock) {
  SimplificationOutcome out;
  const GmshFile input(*request.fine);
  std::unique_ptr<Par> par;
  try {
    QuietStdout quiet;
    par.reset(psurface::GmshIO<float, 2>::readGmsh(input.path()));
  } catch (const std::exception& e) {
    out.error = std::string("PSurface could not read the mesh: ") + e.what();
    return out;
  }
  psurface::QualityRequest quality;
  quality.aspectRatio = float(request.psurface_aspect_ratio);
  quality.hausdorffDistance = float(request.psurface_hausdorff);
  quality.normalize();
  long removed = 0, refused = 0, smoothing_failures = 0;
  GraphFigures before;
  try {
    QuietStdout quiet;
    clock.start();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_seconds();
    par->removeExtraEdges();  // the removal steps work on the graph without its closure
    EdgeTree tree;            // empty: intersections are not checked (QualityRequest's default)
    const int vertex_count = int(par->getNumVertices());
    std::vector<VertexHeap::ErrorValue> costs(static_cast<std::size_t>(vertex_count));
    for (int v = 0; v < vertex_count; ++v) costs[std::size_t(v)] = removal_cost(par.get(), v, quality, tree);
    VertexHeap heap;
    heap.buildHeap(costs);
    while (live_triangles(*par) > std::size_t(request.target_elements)) {
      if (heap.getMin() < 0 || heap.isBlockedMin()) break;
      const int v = heap.extractMin();
      if (remove_vertex(par.get(), v, quality, &tree)) {
        ++removed;
        for (const int w : par->getNeighbors(v)) heap.reposition(w, removal_cost(par.get(), w, quality, tree));
      } else {
        ++refused;
        VertexHeap::ErrorValue blocked = heap.getMinErrorStatus();
        blocked.block();
        heap.insert(v, blocked);
      }
    }
    par->garbageCollection();
    par->hasUpToDatePointLocationStructure = false;
    par->createPointLocationStructure();
    const auto t1 = std::chrono::steady_clock::now();
    out.seconds_simplify = std::chrono::duration<double>(t1 - t0).count();
    out.cpu_simplify = process_cpu_seconds() - c0;
    before = measure_graph(*par);  // not part of either time (it is in the peak-memory window)
    const auto t2 = std::chrono::steady_clock::now();
    const double c2 = process_cpu_seconds();
    if (request.smooth_sweeps > 0) {
      par->removeExtraEdges();
      std::vector<unsigned int> node_stack;
      for (int sweep = 0; sweep < request.smooth_sweeps; ++sweep)
        for (int e = 0; e < int(par->getNumEdges()); ++e) {
          // PSurface's sparse solver gives up on some quadrilaterals (a BiCGSTAB breakdown); the
          // edge then keeps its graph, as plmap's smoothing keeps an element it cannot solve.
          try {
            psurface::PSurfaceSmoother<float>::applyEdgeRelaxation(par.get(), e, false, node_stack);
          } catch (const std::exception&) {
            ++smoothing_failures;
          } catch (...) {
            ++smoothing_failures;
          }
        }
      par->hasUpToDatePointLocationStructure = false;
      par->createPointLocationStructure();
    }
    out.cpu_smooth = process_cpu_seconds() - c2;
    clock.stop();
    out.seconds_smooth = std::chrono::duration<double>(std::chrono::steady_clock::now() - t2).count();
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
    return out;
  } catch (...) {
    clock.stop();
    out.error = "PSurface threw a non-standard exception";
    return out;
  }
  const GraphFigures after = measure_graph(*par);
  const Surface<2> coarse = base_grid(*par);
  const double diagonal = bounding_box_diagonal(*request.fine);
  nlohmann::json f;
  f["elements"] = coarse.element_count();
  f["vertices"] = coarse.vertex_count();
  f["nodes"] = after.nodes;
  f["regions"] = after.kappas.size();
  f["hausdorff_before_smoothing"] = before.hausdorff / diagonal;
  f["hausdorff"] = after.hausdorff / diagonal;
  f["kappa_before"] = kappa_summary(before.kappas);
  f["kappa_after"] = kappa_summary(after.kappas);
  f["coarse_aspect"] = aspect_ratio_json(coarse);
  if (request.refine_levels > 0) {
    long failures = 0;
    f["refined_aspect"] = aspect_ratio_json(refined_through_map(*par, request.refine_levels, failures));
    f["details"]["refined_map_failures"] = failures;
  }
  f["details"]["removed_vertices"] = removed;
  f["details"]["region_area_ratio"] = after.region_area_ratio;
  f["details"]["refused_removals"] = refused;
  f["details"]["smoothing_failures"] = smoothing_failures;
  out.figures = std::move(f);
  out.ok = true;
  return out;
}

}  // namespace plmap::peers
