#include <plmap/verify/generators/closed_surfaces.hpp>

#include <plmap/core/errors.hpp>

#include <cmath>
#include <map>
#include <numbers>

namespace plmap::generators {

Surface<2> icosphere(const SphereOptions& options, Rng& rng) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<WorldPoint<2>> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                  {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<ElementCorners<2>> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < options.subdivisions; ++level) {
    std::map<std::pair<Index, Index>, Index> middle;
    auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      if (auto it = middle.find(key); it != middle.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return middle[key] = static_cast<Index>(v.size() - 1);
    };
    std::vector<ElementCorners<2>> finer;
    for (const auto& c : t) {
      const Index ab = mid(c[0], c[1]), bc = mid(c[1], c[2]), ca = mid(c[2], c[0]);
      finer.push_back({c[0], ab, ca});
      finer.push_back({c[1], bc, ab});
      finer.push_back({c[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    t = std::move(finer);
  }
  if (options.radial_jitter > 0.0)
    for (auto& p : v) p *= uniform_real(rng, 1.0 - options.radial_jitter, 1.0 + options.radial_jitter);
  return Surface<2>(std::move(v), std::move(t));
}

Surface<2> torus(const TorusOptions& o) {
  if (o.around < 3 || o.across < 3 || !(o.minor_radius > 0.0) || !(o.minor_radius < o.major_radius))
    throw Error("torus: needs at least 3 vertices each way and 0 < minor_radius < major_radius");
  std::vector<WorldPoint<2>> v;
  for (int i = 0; i < o.around; ++i)
    for (int j = 0; j < o.across; ++j) {
      const double u = 2.0 * std::numbers::pi * i / o.around, w = 2.0 * std::numbers::pi * j / o.across;
      const double r = o.major_radius + o.minor_radius * std::cos(w);
      v.push_back({r * std::cos(u), r * std::sin(u), o.minor_radius * std::sin(w)});
    }
  std::vector<ElementCorners<2>> t;
  auto at = [&](int i, int j) { return static_cast<Index>((i % o.around) * o.across + j % o.across); };
  for (int i = 0; i < o.around; ++i)
    for (int j = 0; j < o.across; ++j) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return Surface<2>(std::move(v), std::move(t));
}

}  // namespace plmap::generators
