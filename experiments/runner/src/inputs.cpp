#include "inputs.hpp"

#include <plmap/verify/generators/subdivision_maps.hpp>

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/experiment/cgal_data.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/simplified_surface.hpp>

#ifdef PLMAP_EXPERIMENT_PEER_BENCH
#include "peers/inputs.hpp"
#include "peers/plain_mesh_surface.hpp"
#endif

#include <fmt/format.h>

namespace plmap::experiment::detail {

namespace {

using generators::Rng;

/// A planar triangulation lifted onto the input's height field and shifted by its z offset.
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

std::filesystem::path InputCache::cgal_mesh(const std::string& name) { return resolve_cgal_mesh(name, cgal_cache_); }

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
      if (p.integer("simplify_to") > 0) mesh = generators::simplify_by_edge_collapse(mesh, std::size_t(p.integer("simplify_to")));
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
      s = generators::bumpy_grid(int(p.integer("cells")));
    } else if (input.kind == "contact-pair") {
#ifdef PLMAP_EXPERIMENT_PEER_BENCH
      const std::string& which = p.text("case");
      const auto seed = std::uint64_t(p.integer("seed"));
      peers::SurfacePair<2> pair;
      if (which == "plane") pair = peers::facing_planes(long(p.integer("size")), seed);
      else if (which == "sphere") pair = peers::concentric_spheres(int(p.integer("size")), seed);
      else pair = peers::femur_pair(cgal_mesh(p.text("mesh")).string(), which == "femur", seed);
      s = peers::to_surface<2>(pair.s1);
#else
      throw Error("contact-pair inputs need experiments/peers, which this build lacks");
#endif
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
    else if (input.kind == "contact-circles") {
#ifdef PLMAP_EXPERIMENT_PEER_BENCH
      const auto pair = peers::concentric_circles(long(p.integer("segments")), std::uint64_t(p.integer("seed")));
      s = peers::to_surface<1>(pair.s1);
#else
      throw Error("contact-circles inputs need experiments/peers, which this build lacks");
#endif
    }
  }
  if (!s) throw Error(fmt::format("input \"{}\": kind {} does not give a surface of dimension {}", input.name, input.kind, d));
  cache.emplace(cache_key, s);
  return s;
}

template std::shared_ptr<const Surface<1>> InputCache::surface<1>(int, const ParameterSet&);
template std::shared_ptr<const Surface<2>> InputCache::surface<2>(int, const ParameterSet&);

}  // namespace plmap::experiment::detail
