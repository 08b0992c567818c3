#pragma once
/// \file
/// The element searches of normal projection (construct/src/project.cpp): a kd-tree of a
/// surface's element centroids (nanoflann), and NearestElements, which answers a sequence of
/// nearest-centroid queries at nearby points mostly without the tree and always exactly as the
/// tree would.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/surface.hpp>

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace plmap::projection {

/// Element centroids as a nanoflann point cloud.
template <int dim>
struct PointCloud {
  std::vector<Eigen::Matrix<double, dim, 1>> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return points[i](static_cast<int>(k)); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

template <int dim>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud<dim>>,
                                                   PointCloud<dim>, dim, std::uint32_t>;

/// Centroids of a surface's elements, their kd-tree, and the largest centroid-to-corner distance.
template <int d>
struct ElementIndex {
  static constexpr int max_neighbours = 64;
  PointCloud<d + 1> cloud;
  std::unique_ptr<KdTree<d + 1>> tree;
  double radius = 0.0;

  explicit ElementIndex(const Surface<d>& s) {
    // the kd-tree's queries read the centroids at random, and on curves (two trees of a million
    // centroids each) the 4 KiB faults of writing them showed: on huge pages (huge_page_allocator.hpp)
    reserve_for_writing(cloud.points, static_cast<std::size_t>(s.element_count()));
    cloud.points.resize(s.element_count());
    for (Index t = 0; t < s.element_count(); ++t) {
      WorldPoint<d> c = WorldPoint<d>::Zero();
      for (int k = 0; k <= d; ++k) c += s.corner(t, k);
      c /= d + 1;
      cloud.points[t] = c;
      for (int k = 0; k <= d; ++k) radius = std::max(radius, (s.corner(t, k) - c).norm());
    }
    tree = std::make_unique<KdTree<d + 1>>(d + 1, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  }

  Index size() const { return static_cast<Index>(cloud.points.size()); }

  /// Up to `k` (<= max_neighbours) nearest elements, nearest first, and their squared distances.
  int nearest(const WorldPoint<d>& x, int k, std::uint32_t* out, double* squared_distances) const {
    if (cloud.points.empty()) return 0;
    return static_cast<int>(tree->knnSearch(x.data(), static_cast<std::size_t>(k), out, squared_distances));
  }

  /// The squared distance from x to the centroid of element t, computed as nanoflann computes it.
  double squared_distance(const WorldPoint<d>& x, std::uint32_t t) const {
    double result = 0.0;
    for (int k = 0; k <= d; ++k) {
      const double diff = x(k) - cloud.points[t](k);
      result += diff * diff;
    }
    return result;
  }

  /// Whether pred(t) holds for some element t whose centroid lies within r of x. The tree calls
  /// pred while it searches and stops at the first true, without collecting the candidates (the
  /// rim's nearer-sheet test asks this once per rim segment).
  template <class Pred>
  bool any_within(const WorldPoint<d>& x, double r, Pred&& pred) const {
    if (cloud.points.empty()) return false;
    struct StopAtFirst {  // a nanoflann result set
      double squared_radius;
      Pred& pred;
      bool found = false;
      bool full() const { return true; }
      double worstDist() const { return squared_radius; }
      bool addPoint(double squared_distance, std::uint32_t t) {
        if (squared_distance < squared_radius && pred(static_cast<Index>(t))) found = true;
        return !found;
      }
    } result{r * r, pred};
    tree->findNeighbors(result, x.data(), nanoflann::SearchParams());
    return result.found;
  }

  /// The elements whose centroid lies within r of x, in increasing order.
  std::vector<Index> within(const WorldPoint<d>& x, double r) const {
    std::vector<std::pair<std::uint32_t, double>> hits;
    if (!cloud.points.empty()) tree->radiusSearch(x.data(), r * r, hits, nanoflann::SearchParams());
    std::vector<Index> out;
    for (const auto& h : hits) out.push_back(static_cast<Index>(h.first));
    std::sort(out.begin(), out.end());
    return out;
  }
};

/// The k nearest element centroids for a sequence of query points that lie close to each other
/// (the seeds of consecutive vertices of a search chunk), with the same answer as the kd-tree:
/// the same elements in the same order.
///
/// A kd-tree query costs thousands of instructions, most of them descending the tree and
/// checking cells next to the query. Here a wider query (the `wide` nearest centroids of a
/// point c, all of them within radius R of c) is kept and reused: for a query point x at
/// distance delta from c, every centroid within R - delta of x is among the kept ones, so if the
/// (k+1)-th nearest kept centroid lies closer than R - delta, the k nearest kept centroids are the
/// k nearest of all. The answer is taken from the kept centroids only when it is also
/// unambiguous: all k distances differ and the k-th is clearly below the (k+1)-th. With exact
/// ties the tree's order depends on how it visits its cells, and a candidate within rounding of
/// the k-th distance could be pruned by the tree; then the tree answers. Distances are computed
/// exactly as nanoflann computes them, so the order is the same.
template <int d>
class NearestElements {
 public:
  explicit NearestElements(const ElementIndex<d>& index) : index_(index) {}

  /// Up to `k` nearest elements to x, nearest first, as ElementIndex::nearest.
  int nearest(const WorldPoint<d>& x, int k, std::array<std::uint32_t, 32>& out) {
    const int wide = std::min(3 * k, ElementIndex<d>::max_neighbours);
    std::array<double, 32> unused;
    // Small surfaces (all centroids fit into a wide query) and wide k: the tree itself.
    if (index_.size() <= wide) return index_.nearest(x, k, out.data(), unused.data());
    if (kept_ > 0 && from_kept(x, k, out)) {
      ++answers_from_kept_;
      return k;
    }
    refill(x, wide);
    if (from_kept(x, k, out)) return k;
    return index_.nearest(x, k, out.data(), unused.data());
  }

  /// How many answers came from the kept centroids without a tree query (for tests).
  std::size_t answers_from_kept() const { return answers_from_kept_; }

 private:
  void refill(const WorldPoint<d>& x, int wide) {
    std::array<double, ElementIndex<d>::max_neighbours> squared;
    kept_ = index_.nearest(x, wide, kept_ids_.data(), squared.data());
    centre_ = x;
    // Every centroid not kept is at least as far from c as the last kept one (the tree's pruning
    // is exact up to rounding, covered by the margin).
    coverage_ = kept_ == wide ? std::sqrt(squared[kept_ - 1]) * (1.0 - 1e-9) : 0.0;
  }

  bool from_kept(const WorldPoint<d>& x, int k, std::array<std::uint32_t, 32>& out) const {
    if (kept_ <= k) return false;
    // the k + 1 nearest kept centroids, by insertion into a sorted list of k + 1
    std::array<double, 33> squared;
    std::array<std::uint32_t, 33> ids;
    int count = 0;
    for (int i = 0; i < kept_; ++i) {
      const double dist = index_.squared_distance(x, kept_ids_[i]);
      if (count == k + 1 && !(dist < squared[k])) continue;
      int j = count < k + 1 ? count++ : k;
      for (; j > 0 && squared[j - 1] > dist; --j) {
        squared[j] = squared[j - 1];
        ids[j] = ids[j - 1];
      }
      squared[j] = dist;
      ids[j] = kept_ids_[i];
    }
    const double offset = (x - centre_).norm();
    if (!(std::sqrt(squared[k]) + offset < coverage_)) return false;  // the kept ones may not hold the answer
    for (int i = 0; i + 1 < k; ++i)
      if (!(squared[i] < squared[i + 1])) return false;  // a tie: the tree's order decides
    if (!(squared[k - 1] < squared[k] * (1.0 - 1e-12))) return false;
    std::copy(ids.begin(), ids.begin() + k, out.begin());
    return true;
  }

  const ElementIndex<d>& index_;
  WorldPoint<d> centre_ = WorldPoint<d>::Zero();
  double coverage_ = 0.0;
  int kept_ = 0;
  std::size_t answers_from_kept_ = 0;
  std::array<std::uint32_t, ElementIndex<d>::max_neighbours> kept_ids_;
};

}  // namespace plmap::projection
