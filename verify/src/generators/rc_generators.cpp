// RapidCheck generators over the deterministic surface and map generators (rc_generators.hpp).

#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace plmap::generators {

namespace {

/// Seeds are not shrunk: a different seed is a different case, not a simpler one.
rc::Gen<std::uint64_t> seeds() { return rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>()); }

/// Independent streams for the parts of one recipe, so changing one part keeps the others.
Rng stream(std::uint64_t seed, std::uint64_t part) { return Rng(seed ^ (0x9e3779b97f4a7c15ull * (part + 1))); }

const char* name(PlanarBase b) { return b == PlanarBase::grid ? "grid" : "delaunay"; }
const char* name(SheetShape s) {
  switch (s) {
    case SheetShape::planar: return "planar";
    case SheetShape::height_field: return "height_field";
    case SheetShape::fins: return "fins";
    case SheetShape::shared_corner: return "shared_corner";
  }
  return "?";
}
const char* name(CurveShape s) {
  switch (s) {
    case CurveShape::open: return "open";
    case CurveShape::closed: return "closed";
    case CurveShape::star: return "star";
  }
  return "?";
}

}  // namespace

std::string describe(const PlanarRecipe& r) {
  return fmt::format("{} resolution={}{}{} seed={}", name(r.base), r.resolution, r.with_hole ? " hole" : "",
                     r.jitter && r.base == PlanarBase::grid ? " jitter" : "", r.seed);
}
std::string describe(const TriangleSurfaceRecipe& r) {
  return fmt::format("{} over {}", name(r.shape), describe(r.planar));
}
std::string describe(const CurveRecipe& r) {
  return fmt::format("{} curve segments={}{} seed={}", name(r.shape), r.segments,
                     r.shape == CurveShape::star ? fmt::format(" arms={}", r.arms) : "", r.seed);
}

Surface<2> make_planar(const PlanarRecipe& r) {
  Rng rng = stream(r.seed, 0);
  if (r.base == PlanarBase::grid) {
    GridOptions o;
    o.cells = std::max(1, r.resolution);
    if (r.with_hole) o.cells = std::max(4, (o.cells + 3) / 4 * 4);
    o.jitter = r.jitter ? 0.15 : 0.0;
    o.with_hole = r.with_hole;
    return grid_triangulation(o, rng);
  }
  DelaunayOptions o;
  o.interior_points = std::max(0, r.resolution);
  o.boundary_points = 2 + r.resolution / 4;
  o.grid_points = r.resolution / 3;
  o.with_hole = r.with_hole;
  return delaunay_triangulation(o, rng);
}

Surface<2> make_triangle_surface(const TriangleSurfaceRecipe& r) {
  Surface<2> planar = make_planar(r.planar);
  switch (r.shape) {
    case SheetShape::planar: return planar;
    case SheetShape::height_field: {
      Rng rng = stream(r.planar.seed, 1);
      return lift_to_height_field(planar, random_height_field(rng));
    }
    case SheetShape::fins: {
      Rng rng = stream(r.planar.seed, 2);
      Index interior_edges = 0;
      for (Index e = 0; e < planar.edge_count(); ++e) interior_edges += planar.edge_elements(e).size() == 2;
      const int fins = std::min<int>(1 + uniform_index(rng, 2), interior_edges);
      return add_fins(planar, fins, rng);
    }
    case SheetShape::shared_corner: {
      PlanarRecipe second = r.planar;
      second.with_hole = false;
      second.resolution = std::max(1, r.planar.resolution / 2);
      second.seed = r.planar.seed + 1;
      Rng rng = stream(r.planar.seed, 3);
      return join_at_corner(planar, lift_to_height_field(make_planar(second), random_height_field(rng)));
    }
  }
  return planar;
}

Surface<1> make_curve(const CurveRecipe& r) {
  Rng rng = stream(r.seed, 0);
  switch (r.shape) {
    case CurveShape::open: return random_open_polyline(std::max(1, r.segments), rng);
    case CurveShape::closed: return random_closed_polyline(std::max(3, r.segments), rng);
    case CurveShape::star: return random_star_polyline(std::max(3, r.arms), std::max(1, r.segments), rng);
  }
  return random_open_polyline(1, rng);
}

// ---- recipe generators -----------------------------------------------------------------------------

namespace {

rc::Gen<PlanarRecipe> planar_recipes_with(rc::Gen<bool> holes) {
  return rc::gen::withSize([holes](int size) {
    return rc::gen::exec([size, holes] {
      PlanarRecipe r;
      r.base = *rc::gen::element(PlanarBase::grid, PlanarBase::delaunay);
      // ~2 * 6^2 = 72 grid triangles or ~2 * 30 Delaunay triangles at size 100.
      const int max_resolution = r.base == PlanarBase::grid ? 1 + size / 20 : size / 5;
      r.resolution = *rc::gen::inRange(r.base == PlanarBase::grid ? 1 : 0, max_resolution + 1);
      r.with_hole = *holes;
      r.jitter = *rc::gen::arbitrary<bool>();
      r.seed = *seeds();
      return r;
    });
  });
}

}  // namespace

rc::Gen<PlanarRecipe> planar_recipes() { return planar_recipes_with(rc::gen::arbitrary<bool>()); }

rc::Gen<TriangleSurfaceRecipe> triangle_surface_recipes() {
  return rc::gen::exec([] {
    TriangleSurfaceRecipe r;
    r.shape = *rc::gen::element(SheetShape::planar, SheetShape::height_field, SheetShape::fins,
                                SheetShape::shared_corner);
    r.planar = *planar_recipes();
    return r;
  });
}

rc::Gen<CurveRecipe> curve_recipes() {
  return rc::gen::withSize([](int size) {
    return rc::gen::exec([size] {
      CurveRecipe r;
      r.shape = *rc::gen::element(CurveShape::open, CurveShape::closed, CurveShape::star);
      r.arms = *rc::gen::inRange(3, 6);
      const int max_segments = r.shape == CurveShape::star ? 1 + size / 10 : 3 + size / 3;
      r.segments = *rc::gen::inRange(r.shape == CurveShape::closed ? 3 : 1, max_segments + 1);
      r.seed = *seeds();
      return r;
    });
  });
}

rc::Gen<std::shared_ptr<const Surface<2>>> triangle_surfaces() {
  return rc::gen::map(triangle_surface_recipes(), [](const TriangleSurfaceRecipe& r) {
    return std::make_shared<const Surface<2>>(make_triangle_surface(r));
  });
}

rc::Gen<std::shared_ptr<const Surface<1>>> curves() {
  return rc::gen::map(curve_recipes(), [](const CurveRecipe& r) {
    return std::make_shared<const Surface<1>>(make_curve(r));
  });
}

// ---- map generators --------------------------------------------------------------------------------

namespace {

template <int d>
auto surface_recipes() {
  if constexpr (d == 2)
    return triangle_surface_recipes();
  else
    return curve_recipes();
}

template <int d, class Recipe>
std::shared_ptr<const Surface<d>> make_surface_from(const Recipe& r) {
  if constexpr (d == 2)
    return std::make_shared<const Surface<2>>(make_triangle_surface(r));
  else
    return std::make_shared<const Surface<1>>(make_curve(r));
}

}  // namespace

template <int d>
rc::Gen<MapCase<d>> identity_maps() {
  return rc::gen::map(surface_recipes<d>(), [](const auto& r) {
    return identity_map<d>(make_surface_from<d>(r), "identity of " + describe(r));
  });
}

template <int d>
rc::Gen<MapCase<d>> refinement_maps() {
  return rc::gen::exec([] {
    const auto recipe = *surface_recipes<d>();
    RefinementOptions options;
    options.max_points_per_edge = *rc::gen::inRange(0, 3);
    options.max_points_per_element = *rc::gen::inRange(0, 4);
    const std::uint64_t seed = *seeds();
    auto s1 = make_surface_from<d>(recipe);
    Rng rng(seed);
    const Refinement<d> refinement = random_refinement<d>(*s1, options, rng);
    return refinement_map<d>(
        std::move(s1), refinement,
        fmt::format("refinement (edge points <= {}, element points <= {}, seed={}) of {}",
                    options.max_points_per_edge, options.max_points_per_element, seed, describe(recipe)));
  });
}

template <int d>
rc::Gen<MapCase<d>> overlay_maps() {
  if constexpr (d == 2) {
    return rc::gen::exec([] {
      // Both triangulations must cover the same domain: one hole flag for both.
      const bool hole = *rc::gen::arbitrary<bool>();
      const PlanarRecipe r1 = *planar_recipes_with(rc::gen::just(hole));
      const PlanarRecipe r2 = *planar_recipes_with(rc::gen::just(hole));
      return plane_overlay_map(std::make_shared<const Surface<2>>(make_planar(r1)),
                               std::make_shared<const Surface<2>>(make_planar(r2)),
                               fmt::format("overlay of S1 = {} and S2 = {}", describe(r1), describe(r2)));
    });
  } else {
    return rc::gen::exec([] {
      const CurveRecipe recipe = *curve_recipes();
      const int max_splits = *rc::gen::inRange(0, 4);
      const std::uint64_t seed = *seeds();
      Rng rng(seed);
      const PolylineSubdivisions sub =
          random_subdivisions(std::make_shared<const Surface<1>>(make_curve(recipe)), max_splits, rng);
      return polyline_overlay_map(sub, fmt::format("overlay of two subdivisions (splits <= {}, seed={}) of {}",
                                                   max_splits, seed, describe(recipe)));
    });
  }
}

template rc::Gen<MapCase<1>> identity_maps<1>();
template rc::Gen<MapCase<2>> identity_maps<2>();
template rc::Gen<MapCase<1>> refinement_maps<1>();
template rc::Gen<MapCase<2>> refinement_maps<2>();
template rc::Gen<MapCase<1>> overlay_maps<1>();
template rc::Gen<MapCase<2>> overlay_maps<2>();

}  // namespace plmap::generators
