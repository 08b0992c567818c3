#pragma once
// The ray check the projection tests run on their maps: rays along S1's averaged vertex normals
// (the projection's default direction field), 20,000 samples unless told otherwise.

#include <plmap/construct/direction_field.hpp>
#include <plmap/verify/ray_check.hpp>

namespace plmap::test {

inline RayCheckReport<2> rays_along_normals(const PlMap<2>& map, const Surface<2>& s1, std::size_t samples = 20000) {
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(s1);
  o.samples = samples;
  return check_against_rays(map, o);
}

}  // namespace plmap::test
