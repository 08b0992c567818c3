#include <plmap/verify/generators/simplified_surface.hpp>

#include <plmap/core/errors.hpp>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <vector>

namespace plmap::generators {

Surface<2> simplify_by_edge_collapse(const Surface<2>& surface, std::size_t faces) {
  return simplify_by_edge_collapse(surface, faces, EdgeCollapseHooks{});
}

Surface<2> simplify_by_edge_collapse(const Surface<2>& surface, std::size_t faces, const EdgeCollapseHooks& hooks) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (const auto& p : surface.vertices()) v.push_back(mesh.add_vertex({p(0), p(1), p(2)}));
  for (const auto& t : surface.elements())
    if (mesh.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face())
      throw Error("cannot simplify a non-manifold mesh (CGAL rejected a face)");
  namespace SMS = CGAL::Surface_mesh_simplification;
  // CGAL 5.5's stop predicate counts edges; a closed triangle mesh has 3/2 edges per face.
  if (hooks.before_collapse) hooks.before_collapse();
  SMS::edge_collapse(mesh, SMS::Count_stop_predicate<Mesh>(faces * 3 / 2));
  if (hooks.after_collapse) hooks.after_collapse();
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
  return Surface<2>(std::move(vertices), std::move(triangles));
}

}  // namespace plmap::generators
