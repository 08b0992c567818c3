// Every valid map the generators make passes the loader's structural validation
// (map_validation.hpp) and loads back from its file: the validation refuses corrupt files only.
// Corrupting one region neighbour so that it names a region of another element is refused.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/map_validation.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <sstream>

namespace plmap {
namespace {

template <int d>
void check_passes_and_round_trips(const PlMap<d>& map) {
  validate_map_structure(map);  // throws (fails the property) on a false alarm
  std::ostringstream file;
  write_map(file, map);
  const AnyPlMap loaded = parse_map(file.str(), "generated.plmap");
  RC_ASSERT(std::get<PlMap<d>>(loaded).data() == map.data());
}

/// Points one region's neighbour at a region of another element, if the map has two elements
/// with regions; the file of the result must be refused.
template <int d>
void check_foreign_neighbour_is_refused(const PlMap<d>& map) {
  Index from = invalid_index, to = invalid_index;
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    if (map.regions_begin(t) == map.regions_end(t)) continue;
    if (from == invalid_index)
      from = map.regions_begin(t);
    else if (to == invalid_index)
      to = map.regions_begin(t);
  }
  if (to == invalid_index) return;  // one element with regions: nothing to point across
  MapData<d> m = map.data();
  m.region_neighbors[from][*rc::gen::inRange(0, d + 1)] = to;
  const PlMap<d> corrupt(map.domain_ptr(), map.target_ptr(), std::move(m));
  std::ostringstream file;
  write_map(file, corrupt);
  RC_ASSERT_THROWS_AS(parse_map(file.str(), "corrupt.plmap"), InvalidMapError);
}

RC_GTEST_PROP(MapValidationGenerated, RefinementsOfTriangleSurfacesPass, ()) {
  const auto c = *rc::gen::scale(0.5, generators::refinement_maps<2>());
  check_passes_and_round_trips<2>(*c.map);
  check_foreign_neighbour_is_refused<2>(*c.map);
}

RC_GTEST_PROP(MapValidationGenerated, OverlaysOfPlanarTriangulationsPass, ()) {
  const auto c = *rc::gen::scale(0.5, generators::overlay_maps<2>());
  check_passes_and_round_trips<2>(*c.map);
  check_foreign_neighbour_is_refused<2>(*c.map);
}

RC_GTEST_PROP(MapValidationGenerated, CurveOverlaysPass, ()) {
  const auto c = *generators::overlay_maps<1>();
  check_passes_and_round_trips<1>(*c.map);
  check_foreign_neighbour_is_refused<1>(*c.map);
}

}  // namespace
}  // namespace plmap
