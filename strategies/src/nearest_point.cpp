#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/strategies/nearest_point/nearest_point.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <limits>
#include <string>
#include <vector>

namespace plmap {

namespace {

/// Parameter of the point of segment [a, b] nearest to x, in [0, 1].
template <class V>
double clamped_segment_parameter(const V& a, const V& b, const V& x) {
  const V ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return 0.0;
  return std::clamp((x - a).dot(ab) / len2, 0.0, 1.0);
}

using Kernel = CGAL::Simple_cartesian<double>;

/// An AABB-tree primitive: one element as a CGAL segment or triangle (in 3-D; curves at z = 0),
/// its id the element index. The datum is stored in the primitive (no shared data).
template <int d>
struct ElementPrimitive {
  using Id = Index;
  using Datum = std::conditional_t<d == 1, Kernel::Segment_3, Kernel::Triangle_3>;
  using Point = Kernel::Point_3;
  struct Source {
    Datum datum;
    Index id;
  };
  ElementPrimitive() = default;
  template <class Iterator>
  explicit ElementPrimitive(Iterator it) : datum_(it->datum), id_(it->id) {}
  const Datum& datum() const { return datum_; }
  Id id() const { return id_; }
  Point reference_point() const { return datum_.vertex(0); }

 private:
  Datum datum_;
  Id id_ = invalid_index;
};

template <int d>
Kernel::Point_3 to_cgal(const WorldPoint<d>& x) {
  if constexpr (d == 1)
    return {x(0), x(1), 0.0};
  else
    return {x(0), x(1), x(2)};
}

}  // namespace

template <int d>
NearestPoint<d> nearest_point_on_element(const Surface<d>& surface, Index t, const WorldPoint<d>& x) {
  NearestPoint<d> out;
  out.point.element = t;
  const WorldPoint<d>& c0 = surface.corner(t, 0);
  if constexpr (d == 1) {
    out.point.local(0) = clamped_segment_parameter(c0, surface.corner(t, 1), x);
  } else {
    const WorldPoint<2> e1 = surface.corner(t, 1) - c0, e2 = surface.corner(t, 2) - c0, q = x - c0;
    // The projection onto the plane, by the normal equations of [e1 e2] xi = q.
    const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2), p1 = e1.dot(q), p2 = e2.dot(q);
    const double det = a * c - b * b;
    const LocalPoint<2> xi((c * p1 - b * p2) / det, (a * p2 - b * p1) / det);
    if (xi(0) >= 0.0 && xi(1) >= 0.0 && xi(0) + xi(1) <= 1.0) {
      out.point.local = xi;
    } else {
      // Outside the triangle: the nearest point lies on one of its sides.
      double best = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const LocalPoint<2> from = reference_corner<2>(k), to = reference_corner<2>((k + 1) % 3);
        const double s = clamped_segment_parameter(surface.corner(t, k), surface.corner(t, (k + 1) % 3), x);
        const LocalPoint<2> candidate = (1.0 - s) * from + s * to;
        const double dist = (surface.world_position(t, candidate) - x).squaredNorm();
        if (dist < best) best = dist, out.point.local = candidate;
      }
    }
  }
  out.world = surface.world_position(t, out.point.local);
  out.distance = (out.world - x).norm();
  return out;
}

template <int d>
  requires SurfaceDimension<d>
struct AabbNearestPoint<d>::Tree {
  using Primitive = ElementPrimitive<d>;
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> tree;
};

template <int d>
  requires SurfaceDimension<d>
AabbNearestPoint<d>::AabbNearestPoint(std::shared_ptr<const Surface<d>> surface)
    : surface_(std::move(surface)), tree_(std::make_unique<Tree>()) {
  if (surface_->element_count() == 0) throw Error("nearest-point search: the surface has no elements");
  using Source = typename ElementPrimitive<d>::Source;
  std::vector<Source> sources;
  sources.reserve(static_cast<std::size_t>(surface_->element_count()));
  for (Index t = 0; t < surface_->element_count(); ++t) {
    if constexpr (d == 1)
      sources.push_back({{to_cgal<1>(surface_->corner(t, 0)), to_cgal<1>(surface_->corner(t, 1))}, t});
    else
      sources.push_back({{to_cgal<2>(surface_->corner(t, 0)), to_cgal<2>(surface_->corner(t, 1)),
                          to_cgal<2>(surface_->corner(t, 2))},
                         t});
  }
  tree_->tree.insert(sources.begin(), sources.end());
  tree_->tree.build();
  // The distance-query structure is built now, so that concurrent const queries never build it.
  tree_->tree.accelerate_distance_queries();
}

template <int d>
  requires SurfaceDimension<d>
AabbNearestPoint<d>::~AabbNearestPoint() = default;
template <int d>
  requires SurfaceDimension<d>
AabbNearestPoint<d>::AabbNearestPoint(AabbNearestPoint&&) noexcept = default;
template <int d>
  requires SurfaceDimension<d>
AabbNearestPoint<d>& AabbNearestPoint<d>::operator=(AabbNearestPoint&&) noexcept = default;

template <int d>
  requires SurfaceDimension<d>
NearestPoint<d> AabbNearestPoint<d>::nearest(const WorldPoint<d>& x) const {
  if (!x.allFinite()) throw Error("nearest-point search: the query point has non-finite coordinates");
  const auto hit = tree_->tree.closest_point_and_primitive(to_cgal<d>(x));
  return nearest_point_on_element(*surface_, hit.second, x);
}

template <int d>
  requires SurfaceDimension<d>
NearestPoint<d> BruteForceNearestPoint<d>::nearest(const WorldPoint<d>& x) const {
  if (!x.allFinite()) throw Error("nearest-point search: the query point has non-finite coordinates");
  if (surface_->element_count() == 0) throw Error("nearest-point search: the surface has no elements");
  NearestPoint<d> best;
  best.distance = std::numeric_limits<double>::infinity();
  for (Index t = 0; t < surface_->element_count(); ++t) {
    const NearestPoint<d> p = nearest_point_on_element(*surface_, t, x);
    if (p.distance < best.distance) best = p;
  }
  return best;
}

template <int d>
void nearest_points_batch(const AabbNearestPoint<d>& index, std::span<const WorldPoint<d>> points,
                          std::span<NearestPoint<d>> out, unsigned threads) {
  if (out.size() != points.size()) throw Error("nearest_points_batch: output span size differs from the number of points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw Error("nearest-point search: point " + std::to_string(i) + " has non-finite coordinates");
  parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) out[i] = index.nearest(points[i]);
  });
}

template void nearest_points_batch(const AabbNearestPoint<1>&, std::span<const WorldPoint<1>>, std::span<NearestPoint<1>>,
                                   unsigned);
template void nearest_points_batch(const AabbNearestPoint<2>&, std::span<const WorldPoint<2>>, std::span<NearestPoint<2>>,
                                   unsigned);
template NearestPoint<1> nearest_point_on_element(const Surface<1>&, Index, const WorldPoint<1>&);
template NearestPoint<2> nearest_point_on_element(const Surface<2>&, Index, const WorldPoint<2>&);
template class AabbNearestPoint<1>;
template class AabbNearestPoint<2>;
template class BruteForceNearestPoint<1>;
template class BruteForceNearestPoint<2>;

}  // namespace plmap
