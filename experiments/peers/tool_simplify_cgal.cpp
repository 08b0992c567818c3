// The floor of the simplification benchmark: CGAL's edge-collapse simplification
// (Surface_mesh_simplification, Lindstrom-Turk placement and cost), which decimates without
// keeping a map, on the same mesh to the same number of triangles.

#include "simplification_tools.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <exception>

namespace plmap::peers {

SimplificationOutcome simplify_with_cgal(const SimplificationRequest& request, Measurement& clock) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  namespace SMS = CGAL::Surface_mesh_simplification;
  SimplificationOutcome out;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (const auto& p : request.fine->vertices()) v.push_back(mesh.add_vertex({p(0), p(1), p(2)}));
  for (const auto& t : request.fine->elements())
    if (mesh.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face()) {
      out.error = "CGAL's Surface_mesh rejected a face (non-manifold mesh)";
      return out;
    }
  try {
    clock.start();
    const double c0 = process_cpu_seconds();
    // CGAL 5.5's stop predicate counts edges: a closed triangle mesh has 3/2 edges per face.
    SMS::edge_collapse(mesh, SMS::Count_stop_predicate<Mesh>(static_cast<std::size_t>(request.target_elements) * 3 / 2));
    out.cpu_simplify = process_cpu_seconds() - c0;
    clock.stop();
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
    return out;
  }
  out.seconds_simplify = clock.seconds();
  mesh.collect_garbage();
  std::vector<WorldPoint<2>> vertices;
  for (auto vi : mesh.vertices()) {
    const auto& p = mesh.point(vi);
    vertices.push_back({p.x(), p.y(), p.z()});
  }
  std::vector<ElementCorners<2>> triangles;
  for (auto f : mesh.faces()) {
    ElementCorners<2> c;
    int k = 0;
    for (auto vi : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) c[k++] = Index(vi.idx());
    triangles.push_back(c);
  }
  const Surface<2> coarse(std::move(vertices), std::move(triangles));
  out.figures["elements"] = coarse.element_count();
  out.figures["vertices"] = coarse.vertex_count();
  out.figures["coarse_aspect"] = aspect_ratio_json(coarse);
  out.ok = true;
  return out;
}

}  // namespace plmap::peers
