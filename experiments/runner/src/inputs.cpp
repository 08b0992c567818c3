#include "inputs.hpp"

#include "refinement_maps.hpp"  // tests/strategies: bumpy_grid, shared with the benchmarks

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/experiment/cgal_data.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <fmt/format.h>

namespace plmap::experiment::detail {

namespace {

using generators::Rng;

/// `surface` simplified by CGAL's edge collapse (default cost and placement: Lindstrom-Turk) to
/// about `faces` triangles. Deterministic: the collapse order depends only on the mesh.
Surface<2> simplify(const Surface<2>& surface, std::size_t faces) {
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
  SMS::edge_collapse(mesh, SMS::Count_stop_predicate<Mesh>(faces * 3 / 2));
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

Surface<2> shaped(const Surface<2>& planar, const ParameterSet& p) {
  Surface<2> s = p.real("height") > 0
                     ? generators::lift_to_height_field(planar, generators::HeightField{.amplitude = p.real("height")})
                     : planar;
  if (p.real("z_offset") == 0) return s;
  auto vertices = s.vertices();
  for (auto& x : vertices) x(2) += p.real("z_offset");
  return Surface<2>(std::move(vertices), s.elements());
}

}  // namespace

template <int d>
std::shared_ptr<const Surface<d>> InputCache::surface(int index, const ParameterSet& p) {
  const InputConfig& input = config_.inputs[index];
  std::string cache_key = input.kind;
  for (const auto& [k, v] : p.entries()) cache_key += "|" + k + "=" + to_text(v);
  auto& cache = [&]() -> auto& {
    if constexpr (d == 1) return curves_;
    else return surfaces_;
  }();
  if (auto it = cache.find(cache_key); it != cache.end()) return it->second;

  std::shared_ptr<const Surface<d>> s;
  auto rng = [&] { return Rng(std::uint64_t(p.integer("seed"))); };
  if (input.kind == "file") {
    std::filesystem::path path = p.text("path");
    if (path.is_relative()) path = config_.base_directory / path;
    s = std::make_shared<const Surface<d>>(read_surface<d>(path));
  } else if constexpr (d == 2) {
    if (input.kind == "cgal") {
      Surface<2> mesh = read_surface<2>(resolve_cgal_mesh(p.text("mesh"), cgal_cache_));
      if (p.integer("simplify_to") > 0) mesh = simplify(mesh, std::size_t(p.integer("simplify_to")));
      s = std::make_shared<const Surface<2>>(std::move(mesh));
    } else if (input.kind == "grid") {
      Rng r = rng();
      const auto planar = generators::grid_triangulation(
          {.cells = int(p.integer("cells")), .jitter = p.real("jitter"), .with_hole = p.boolean("hole")}, r);
      s = std::make_shared<const Surface<2>>(shaped(planar, p));
    } else if (input.kind == "delaunay") {
      Rng r = rng();
      const auto planar = generators::delaunay_triangulation({.interior_points = int(p.integer("interior_points")),
                                                              .boundary_points = int(p.integer("boundary_points")),
                                                              .grid_points = int(p.integer("grid_points")),
                                                              .with_hole = p.boolean("hole")},
                                                             r);
      s = std::make_shared<const Surface<2>>(shaped(planar, p));
    } else if (input.kind == "bumpy-grid") {
      s = testing::bumpy_grid(int(p.integer("cells")));
    }
  } else {
    Rng r = rng();
    if (input.kind == "open-polyline")
      s = std::make_shared<const Surface<1>>(generators::random_open_polyline(int(p.integer("segments")), r));
    else if (input.kind == "closed-polyline")
      s = std::make_shared<const Surface<1>>(generators::random_closed_polyline(int(p.integer("segments")), r));
    else if (input.kind == "star-polyline")
      s = std::make_shared<const Surface<1>>(
          generators::random_star_polyline(int(p.integer("arms")), int(p.integer("segments_per_arm")), r));
  }
  if (!s) throw Error(fmt::format("input \"{}\": kind {} does not give a surface of dimension {}", input.name, input.kind, d));
  cache.emplace(cache_key, s);
  return s;
}

template std::shared_ptr<const Surface<1>> InputCache::surface<1>(int, const ParameterSet&);
template std::shared_ptr<const Surface<2>> InputCache::surface<2>(int, const ParameterSet&);

}  // namespace plmap::experiment::detail
