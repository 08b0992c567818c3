// averaged_vertex_normals spreads its vertices over threads: the normals are the same, to the
// bit, for every thread count (the projection's set-up computes them with its thread count).

#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

TEST(DirectionFieldThreads, AveragedNormalsDoNotDependOnTheThreadCount) {
  // more vertices than one chunk of 4096, on a curved surface so the normals differ
  const auto s = test::sphere(6, 1.0);
  ASSERT_GT(s->vertex_count(), 3 * 4096);
  const auto one = averaged_vertex_normals(*s);
  ASSERT_EQ(one.size(), static_cast<std::size_t>(s->vertex_count()));
  for (const unsigned threads : {2u, 3u, 0u}) {
    const auto many = averaged_vertex_normals(*s, threads);
    ASSERT_EQ(many.size(), one.size());
    std::size_t differing = 0;
    for (std::size_t v = 0; v < one.size(); ++v) differing += many[v] != one[v];
    EXPECT_EQ(differing, 0u) << threads << " threads";
  }
  // and they are the unit outward normals of the sphere, about
  for (Index v = 0; v < s->vertex_count(); ++v) EXPECT_GT(one[v].dot(s->vertex(v).normalized()), 0.99);
}

}  // namespace
}  // namespace plmap
