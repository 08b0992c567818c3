#pragma once
/// \file
/// plmap's normal projection as a dune-grid-glue merger: a drop-in replacement for
/// Dune::GridGlue::ContactMerge on 1-D interfaces of 2-D grids (dimworld = 2) and 2-D interfaces
/// of 3-D grids (dimworld = 3).
///
///   // auto merger = std::make_shared<Dune::GridGlue::ContactMerge<dimworld, double>>();
///   auto merger = std::make_shared<plmap::dune::PlmapMerge<dimworld>>();
///   Dune::GridGlue::GridGlue<Extractor0, Extractor1> glue(patch0, patch1, merger);
///   glue.build();
///
/// Grid 0 (the first patch) is S1 and is projected along its outer normal field onto grid 1 (S2),
/// as ContactMerge's default OUTER_NORMAL projection does. Every intersection is one region of the
/// resulting map (core/regions.hpp): a segment or triangle with one parent element on each side
/// and its corners in local coordinates of both parents, listed in the same order on both sides.
/// The map, the projection's report (what could not be inserted and why) and the covered measures
/// stay available after build() (projection()).
///
/// Errors: an element that is not a simplex (the extractors of dune-grid-glue split
/// quadrilaterals into triangles, so they never give one) raises plmap::Error naming the grid and
/// the element; invalid grids raise plmap::InvalidSurfaceError, bad options plmap::Error
/// (core/errors.hpp). On an error the previous intersection list is cleared.

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/core/surface.hpp>

#include <dune/common/fvector.hh>
#include <dune/geometry/type.hh>
#include <dune/grid-glue/merging/intersectionlist.hh>
#include <dune/grid-glue/merging/merger.hh>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace plmap::dune {

/// Which direction field grid 0 is projected along when PlmapMerge has no analytic field.
enum class NormalAveraging {
  /// The normalised sum of the unit normals of the elements at each vertex: ContactMerge's
  /// field (its computeOuterNormalField), so that both mergers project along the same rays and
  /// a swap changes nothing but the algorithm. Default.
  unit_element_normals,
  /// plmap's own averaged vertex normals, weighted by element measure
  /// (construct/direction_field.hpp, averaged_vertex_normals): better on graded grids.
  measure_weighted,
};

/// Everything PlmapMerge can be told, with ContactMerge-compatible defaults.
template <int dimworld>
struct PlmapMergeOptions {
  using WorldCoords = ::Dune::FieldVector<double, dimworld>;

  /// The options of plmap::project (construct/projection_options.hpp): distance bound
  /// (max_distance, max_distance_is_relative), negative distances (allow_negative_distance, as
  /// ContactMerge's allowedOverlap), target normal check, threads (0 = all cores), solver.
  /// A non-empty `projection.directions` (d+1 numbers per grid-0 vertex, in the order of the
  /// coordinates build() receives) is used as given and overrides the two fields below.
  ProjectionOptions projection = {};
  /// An analytic direction field sampled at the grid-0 vertices, like ContactMerge's
  /// domainDirections; it need not be normalised. Empty: averaged normals (`averaging`).
  std::function<WorldCoords(WorldCoords)> directions = nullptr;
  NormalAveraging averaging = NormalAveraging::unit_element_normals;
};

template <int dimworld>
class PlmapMerge : public ::Dune::GridGlue::Merger<double, dimworld - 1, dimworld - 1, dimworld> {
  static_assert(dimworld == 2 || dimworld == 3,
                "PlmapMerge couples 1-D interfaces of 2-D grids or 2-D interfaces of 3-D grids");
  static constexpr int d = dimworld - 1;
  using Base = ::Dune::GridGlue::Merger<double, d, d, dimworld>;
  using Provider = ::Dune::GridGlue::SimplicialIntersectionListProvider<d, d>;

 public:
  using WorldCoords = typename Base::WorldCoords;
  using IntersectionList = typename Base::IntersectionList;
  using Options = PlmapMergeOptions<dimworld>;

  explicit PlmapMerge(Options options = {})
      : options_(std::move(options)),
        provider_(std::make_shared<Provider>()),
        list_(std::make_shared<IntersectionList>(provider_)) {}

  const Options& options() const { return options_; }
  /// New options take effect at the next build().
  void set_options(Options options) { options_ = std::move(options); }

  void build(const std::vector<WorldCoords>& grid1_coords, const std::vector<unsigned int>& grid1_elements,
             const std::vector<::Dune::GeometryType>& grid1_element_types,
             const std::vector<WorldCoords>& grid2_coords, const std::vector<unsigned int>& grid2_elements,
             const std::vector<::Dune::GeometryType>& grid2_element_types) override {
    clear();
    result_.reset();
    auto s1 = to_surface(grid1_coords, grid1_elements, grid1_element_types, "grid 0");
    auto s2 = to_surface(grid2_coords, grid2_elements, grid2_element_types, "grid 1");
    ProjectionOptions projection = options_.projection;
    if (projection.directions.empty()) projection.directions = direction_values(grid1_coords, *s1);
    result_.emplace(project<d>(std::move(s1), std::move(s2), projection));

    const auto& map = result_->map;
    auto& intersections = provider_->intersections();
    intersections.reserve(static_cast<std::size_t>(map.region_count()));
    for (Index r = 0; r < map.region_count(); ++r) {
      const RemoteIntersection<d> piece = remote_intersection(map, r);
      typename Provider::SimplicialIntersection out(static_cast<unsigned>(piece.domain_element),
                                                     static_cast<unsigned>(piece.target_element));
      for (int k = 0; k <= d; ++k)
        for (int j = 0; j < d; ++j) {
          out.corners0[0][k][j] = piece.domain_local[k](j);
          out.corners1[0][k][j] = piece.target_local[k](j);
        }
      intersections.push_back(std::move(out));
    }
  }

  /// Frees the intersection list. GridGlue calls it right after copying the list, so the
  /// projection (map and report) is kept until the next build().
  void clear() override { provider_->clear(); }

  std::shared_ptr<IntersectionList> intersectionList() const override { return list_; }

  /// The last build's map (grid-0 boundary elements -> grid-1 boundary elements), report and
  /// covered measures; throws plmap::Error before the first successful build().
  const ProjectionResult<d>& projection() const {
    if (!result_) throw Error("PlmapMerge::projection(): no map; call build() first");
    return *result_;
  }

 private:
  static std::shared_ptr<const Surface<d>> to_surface(const std::vector<WorldCoords>& coords,
                                                       const std::vector<unsigned int>& corners,
                                                       const std::vector<::Dune::GeometryType>& types,
                                                       const std::string& grid) {
    std::vector<WorldPoint<d>> points(coords.size());
    for (std::size_t v = 0; v < coords.size(); ++v)
      for (int k = 0; k < dimworld; ++k) points[v](k) = coords[v][k];
    for (std::size_t e = 0; e < types.size(); ++e)
      if (!types[e].isSimplex() || static_cast<int>(types[e].dim()) != d)
        throw Error("PlmapMerge: " + grid + " element " + std::to_string(e) + " is not a " +
                    (d == 1 ? "segment" : "triangle") + "; the merger takes simplices only");
    if (corners.size() != types.size() * static_cast<std::size_t>(d + 1))
      throw Error("PlmapMerge: " + grid + " has " + std::to_string(types.size()) + " element types but " +
                  std::to_string(corners.size()) + " corner indices (expected " + std::to_string(d + 1) +
                  " per element)");
    std::vector<ElementCorners<d>> elements(types.size());
    for (std::size_t e = 0; e < types.size(); ++e) {
      for (int k = 0; k <= d; ++k) {
        const unsigned vertex = corners[e * (d + 1) + static_cast<std::size_t>(k)];
        if (vertex >= coords.size())
          throw InvalidSurfaceError("PlmapMerge: " + grid + " element " + std::to_string(e) + " corner " +
                                    std::to_string(k) + " is vertex " + std::to_string(vertex) + ", but there are " +
                                    std::to_string(coords.size()) + " vertices");
        elements[e][static_cast<std::size_t>(k)] = static_cast<Index>(vertex);
      }
    }
    return std::make_shared<const Surface<d>>(std::move(points), std::move(elements));
  }

  /// The projection directions at the grid-0 vertices, d+1 numbers per vertex.
  std::vector<double> direction_values(const std::vector<WorldCoords>& coords, const Surface<d>& s1) const {
    std::vector<double> values(coords.size() * dimworld, 0.0);
    const auto store = [&](std::size_t v, const auto& direction) {
      for (int k = 0; k < dimworld; ++k) values[v * dimworld + static_cast<std::size_t>(k)] = direction[k];
    };
    if (options_.directions) {
      for (std::size_t v = 0; v < coords.size(); ++v) store(v, options_.directions(coords[v]));
      return values;
    }
    if (options_.averaging == NormalAveraging::measure_weighted) {
      const auto normals = averaged_vertex_normals<d>(s1);
      for (std::size_t v = 0; v < coords.size(); ++v) store(v, normals[v]);
    } else {
      std::vector<WorldPoint<d>> sums(coords.size(), WorldPoint<d>::Zero());
      for (Index e = 0; e < s1.element_count(); ++e)
        for (Index v : s1.element(e)) sums[static_cast<std::size_t>(v)] += s1.element_normal(e);
      for (std::size_t v = 0; v < coords.size(); ++v) {
        const auto around = s1.vertex_elements(static_cast<Index>(v));
        // Where the unit normals cancel (a fold of the grid) ContactMerge would divide by zero;
        // take the first element's normal, as averaged_vertex_normals does.
        if (!around.empty() && sums[v].norm() < 1e-8 * static_cast<double>(around.size()))
          sums[v] = s1.element_normal(around.front());
        store(v, sums[v]);
      }
    }
    // A vertex in no element has the zero direction, which plmap rejects; it needs none, so
    // give it any unit vector.
    for (std::size_t v = 0; v < coords.size(); ++v)
      if (s1.vertex_elements(static_cast<Index>(v)).empty()) values[v * dimworld] = 1.0;
    return values;
  }

  Options options_;
  std::shared_ptr<Provider> provider_;
  std::shared_ptr<IntersectionList> list_;
  std::optional<ProjectionResult<d>> result_;
};

}  // namespace plmap::dune
