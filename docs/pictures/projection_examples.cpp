// The two projection maps of docs/drawing.md (the `plmap build` command has no projection yet):
// a coarse arc projected onto a wavy curve (paper Fig. 1) and a coarse sphere onto a finer one
// (paper Fig. 2). Built and run by make_pictures.sh; argument: the directory of the CGAL meshes.
#include <plmap/construct/project.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <cmath>
#include <iostream>
#include <string>
using namespace plmap;
int main(int argc, char** argv) {
  const std::string meshes = argc > 1 ? argv[1] : "data/meshes";
  // d = 1: S1 a coarse arc, S2 a wavy finer curve above it; projected along S1's normals.
  std::vector<WorldPoint<1>> v1, v2;
  std::vector<ElementCorners<1>> e1, e2;
  const int n1 = 6, n2 = 11;
  for (int i = 0; i <= n1; ++i) { double x = double(i) / n1; v1.push_back({x, 0.15 * std::sin(3.0 * x)}); }
  for (int i = 0; i + 1 < (int)v1.size(); ++i) e1.push_back({i + 1, i});  // normals (clockwise rotation) point up
  for (int i = 0; i <= n2; ++i) { double x = -0.05 + 1.1 * double(i) / n2; v2.push_back({x, 0.35 + 0.15 * std::sin(3.0 * x) + 0.05 * std::sin(17.0 * x)}); }
  for (int i = 0; i + 1 < (int)v2.size(); ++i) e2.push_back({i, i + 1});
  auto s1 = std::make_shared<const Surface<1>>(v1, e1);
  auto s2 = std::make_shared<const Surface<1>>(v2, e2);
  auto r = project<1>(s1, s2);
  save_map("curves_projection.plmap", r.map);
  std::cout << "d=1 nodes " << r.map.node_count() << "\n";
  // d = 2: coarse sphere onto a finer sphere (paper Fig. 2).
  auto a = std::make_shared<const Surface<2>>(read_surface<2>(meshes + "/sphere.off"));
  const Surface<2> fine = read_surface<2>(meshes + "/sphere966.off");
  auto scaled = fine.vertices();  // sphere966 has radius 10, sphere.off radius 0.5
  for (auto& p : scaled) p *= 0.05;
  auto b = std::make_shared<const Surface<2>>(scaled, fine.elements());
  ProjectionOptions o;
  o.allow_negative_distance = true;
  auto r2 = project<2>(a, b, o);
  save_map("sphere_projection.plmap", r2.map);
  std::cout << "d=2 nodes " << r2.map.node_count() << "\n";
}
