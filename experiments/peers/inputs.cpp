#include "inputs.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>

namespace plmap::peers {

template <>
double PlainMesh<1>::cell_measure(std::size_t c) const {
  const auto& a = points[cells[c][0]];
  const auto& b = points[cells[c][1]];
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

template <>
double PlainMesh<2>::cell_measure(std::size_t c) const {
  const auto& a = points[cells[c][0]];
  const auto& b = points[cells[c][1]];
  const auto& p = points[cells[c][2]];
  const Eigen::Vector3d u(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
  const Eigen::Vector3d v(p[0] - a[0], p[1] - a[1], p[2] - a[2]);
  return 0.5 * u.cross(v).norm();
}

template <int d>
double PlainMesh<d>::measure() const {
  double sum = 0.0;
  for (std::size_t c = 0; c < cells.size(); ++c) sum += cell_measure(c);
  return sum;
}

template struct PlainMesh<1>;
template struct PlainMesh<2>;

namespace {

/// Reverses the orientation of every cell (normals flip).
template <int d>
void reverse_orientation(PlainMesh<d>& mesh) {
  for (auto& c : mesh.cells) std::swap(c[0], c[1]);
}

/// A jittered n x m grid of cells over [x0, x0+1] x [y0, y0+1] at height z, each cell split along a
/// random diagonal, counter-clockwise seen from +z. Boundary vertices move only along the boundary,
/// so the patch stays exactly the square and the overlap of two patches is known.
PlainMesh<2> jittered_grid(int n, double x0, double y0, double z, std::mt19937_64& rng) {
  const double h = 1.0 / n;
  std::uniform_real_distribution<double> jitter(-0.2 * h, 0.2 * h);
  std::bernoulli_distribution diagonal(0.5);
  PlainMesh<2> mesh;
  mesh.points.reserve(std::size_t(n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double dx = (i == 0 || i == n) ? 0.0 : jitter(rng);
      const double dy = (j == 0 || j == n) ? 0.0 : jitter(rng);
      mesh.points.push_back({x0 + i * h + dx, y0 + j * h + dy, z});
    }
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  mesh.cells.reserve(2 * std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
      if (diagonal(rng)) {
        mesh.cells.push_back({a, b, c});
        mesh.cells.push_back({a, c, e});
      } else {
        mesh.cells.push_back({a, b, e});
        mesh.cells.push_back({b, c, e});
      }
    }
  return mesh;
}

/// Geodesic icosphere: each icosahedron face cut into frequency^2 triangles, vertices pushed onto
/// the sphere of the given radius; outward orientation.
PlainMesh<2> geodesic_sphere(int frequency, double radius, const Eigen::Matrix3d& rotation) {
  const double phi = std::numbers::phi;
  const std::array<Eigen::Vector3d, 12> ico = {
      Eigen::Vector3d(-1, phi, 0), Eigen::Vector3d(1, phi, 0),  Eigen::Vector3d(-1, -phi, 0),
      Eigen::Vector3d(1, -phi, 0), Eigen::Vector3d(0, -1, phi), Eigen::Vector3d(0, 1, phi),
      Eigen::Vector3d(0, -1, -phi), Eigen::Vector3d(0, 1, -phi), Eigen::Vector3d(phi, 0, -1),
      Eigen::Vector3d(phi, 0, 1),  Eigen::Vector3d(-phi, 0, -1), Eigen::Vector3d(-phi, 0, 1)};
  std::array<std::array<int, 3>, 20> faces = {{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}}};
  for (auto& f : faces) {
    const Eigen::Vector3d n = (ico[f[1]] - ico[f[0]]).cross(ico[f[2]] - ico[f[0]]);
    if (n.dot(ico[f[0]]) < 0) std::swap(f[1], f[2]);
  }
  // A point of the subdivision is named by its integer barycentric weights on the icosahedron
  // vertices (sorted by vertex), so points on shared edges and corners are found once.
  std::map<std::array<int, 6>, int> index_of;
  PlainMesh<2> mesh;
  const auto point = [&](const std::array<int, 3>& f, int i, int j) {
    const std::array<std::pair<int, int>, 3> weights = {
        std::pair{f[0], frequency - i - j}, std::pair{f[1], i}, std::pair{f[2], j}};
    std::array<std::pair<int, int>, 3> sorted = weights;
    for (auto& [v, w] : sorted)
      if (w == 0) v = -1;  // a vertex with weight zero does not name the point
    std::sort(sorted.begin(), sorted.end());
    std::array<int, 6> key{};
    for (int k = 0; k < 3; ++k) {
      key[2 * k] = sorted[k].first;
      key[2 * k + 1] = sorted[k].second;
    }
    const auto [it, inserted] = index_of.try_emplace(key, static_cast<int>(mesh.points.size()));
    if (inserted) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (const auto& [v, w] : weights) p += double(w) * ico[v];
      p = rotation * (radius * p.normalized());
      mesh.points.push_back({p.x(), p.y(), p.z()});
    }
    return it->second;
  };
  for (const auto& f : faces)
    for (int j = 0; j < frequency; ++j)
      for (int i = 0; i + j < frequency; ++i) {
        mesh.cells.push_back({point(f, i, j), point(f, i + 1, j), point(f, i, j + 1)});
        if (i + j + 1 < frequency)
          mesh.cells.push_back({point(f, i + 1, j), point(f, i + 1, j + 1), point(f, i, j + 1)});
      }
  return mesh;
}

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

}  // namespace

SurfacePair<2> facing_planes(long s1_triangles, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(double(s1_triangles) / 2.0))));
  const int m = static_cast<int>(std::lround(1.3 * n));
  SurfacePair<2> pair;
  pair.family = "plane";
  pair.s1 = jittered_grid(n, 0.0, 0.0, 0.0, rng);
  pair.s2 = jittered_grid(m, 0.2, 0.1, 0.5 / n, rng);
  reverse_orientation(pair.s2);
  pair.label = fmt::format("plane {}x{}", pair.s1.cells.size(), pair.s2.cells.size());
  pair.exact_overlap = 0.8 * 0.9;
  pair.exact_target_overlap = 0.8 * 0.9;
  pair.exact_overlap_note = "area of [0,1]^2 ∩ [0.2,1.2]x[0.1,1.1]";
  return pair;
}

SurfacePair<2> concentric_spheres(int level, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int f = 1 << level;
  SurfacePair<2> pair;
  pair.family = "sphere";
  pair.s1 = geodesic_sphere(f, 1.0, Eigen::Matrix3d::Identity());
  pair.s2 = geodesic_sphere(f + 1, 1.01, random_rotation(rng));
  reverse_orientation(pair.s2);
  pair.label = fmt::format("sphere L{} {}x{}", level, pair.s1.cells.size(), pair.s2.cells.size());
  pair.exact_overlap = pair.s1.measure();
  pair.exact_target_overlap = pair.s2.measure();
  pair.exact_overlap_note = "area of S1 (closed, entirely covered)";
  return pair;
}

SurfacePair<2> femur_pair(const std::string& off_file, bool remesh, std::uint64_t seed) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  namespace PMP = CGAL::Polygon_mesh_processing;
  Mesh original;
  if (!CGAL::IO::read_polygon_mesh(off_file, original) || original.is_empty())
    throw std::runtime_error(fmt::format("{}: cannot read the mesh", off_file));
  if (!PMP::is_outward_oriented(original)) PMP::reverse_face_orientations(original);

  double mean_edge = 0.0;
  for (auto e : original.edges()) mean_edge += PMP::edge_length(e, original);
  mean_edge /= double(original.number_of_edges());

  // A different triangulation of the same shape: isotropic remeshing to 0.8 of the mean edge
  // length (about twice the triangles), then an offset along the vertex normals, large enough
  // (a quarter of the mean edge) that the remeshed faces, which cut S1's curved parts, stay
  // outside S1.
  Mesh remeshed = original;
  if (remesh)
    PMP::isotropic_remeshing(faces(remeshed), 0.8 * mean_edge, remeshed, CGAL::parameters::number_of_iterations(3));
  remeshed.collect_garbage();
  auto normals = remeshed.add_property_map<Mesh::Vertex_index, Kernel::Vector_3>("v:n").first;
  PMP::compute_vertex_normals(remeshed, normals);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> gap(0.2 * mean_edge, 0.3 * mean_edge);
  for (auto v : remeshed.vertices()) remeshed.point(v) = remeshed.point(v) + gap(rng) * normals[v];

  const auto to_plain = [](const Mesh& mesh) {
    PlainMesh<2> out;
    std::map<Mesh::Vertex_index, int> index;
    for (auto v : mesh.vertices()) {
      index[v] = static_cast<int>(out.points.size());
      const auto& p = mesh.point(v);
      out.points.push_back({p.x(), p.y(), p.z()});
    }
    for (auto f : mesh.faces()) {
      std::array<int, 3> cell{};
      int k = 0;
      for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) cell[k++] = index[v];
      out.cells.push_back(cell);
    }
    return out;
  };
  SurfacePair<2> pair;
  pair.family = remesh ? "femur" : "femur-offset";
  pair.s1 = to_plain(original);
  pair.s2 = to_plain(remeshed);
  reverse_orientation(pair.s2);
  pair.label = fmt::format("{} {}x{}", pair.family, pair.s1.cells.size(), pair.s2.cells.size());
  pair.exact_overlap = pair.s1.measure();
  pair.exact_target_overlap = pair.s2.measure();
  pair.exact_overlap_note = "area of S1 (closed, inside a close offset of itself)";
  return pair;
}

SurfacePair<1> concentric_circles(long s1_segments, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const long n = std::max(3L, s1_segments);
  const long m = std::lround(1.3 * double(n));
  const double turn = 2.0 * std::numbers::pi;
  const double rotation = std::uniform_real_distribution<double>(0.0, turn)(rng);
  SurfacePair<1> pair;
  pair.family = "circle";
  for (long k = 0; k < n; ++k) {
    const double t = turn * double(k) / double(n);
    pair.s1.points.push_back({std::cos(t), std::sin(t)});
    pair.s1.cells.push_back({int(k), int((k + 1) % n)});
  }
  for (long k = 0; k < m; ++k) {
    const double t = rotation + turn * double(k) / double(m);
    pair.s2.points.push_back({1.01 * std::cos(t), 1.01 * std::sin(t)});
    pair.s2.cells.push_back({int((k + 1) % m), int(k)});  // clockwise: normals point inward
  }
  pair.label = fmt::format("circle {}x{}", n, m);
  pair.exact_overlap = pair.s1.measure();
  pair.exact_target_overlap = pair.s2.measure();
  pair.exact_overlap_note = "length of S1 (closed, entirely covered)";
  return pair;
}

}  // namespace plmap::peers
