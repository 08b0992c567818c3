// Normal projection, phase 1: ghost rays (projection_ghost_rays.hpp).

#include "projection_ghost_rays.hpp"

#include "projection_seeds.hpp"

#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/small_lu.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap::projection {

namespace {

/// The rays of one chunk of S1 vertices.
template <int d>
class GhostRays {
 public:
  explicit GhostRays(const ProjectionContext<d>& ctx) : ctx_(ctx) {}

  /// The ray from S1 vertex v; `mu` is the ray parameter of the chunk's previous hit (see
  /// search_chunk), updated on return.
  std::optional<SurfacePoint<d>> cast_ray(Index v, std::optional<double>& mu, NearestElements<d>& nearest) {
    const WorldPoint<d>& direction = ctx_.vertex_directions[v];
    std::optional<SurfacePoint<d>> hit;
    outside_band_ = std::numeric_limits<float>::quiet_NaN();
    // Seeds next to the previous vertex's hit (v moved by its ray parameter) are for S2 many
    // element sizes away, where a search from v visits O(gap / h) kd-tree leaves. They lie on
    // the sheet of S2 that the previous ray reached, and a nearer sheet that this ray meets
    // first is found only from the elements nearest to v (the bones of a joint, whose gap is
    // smaller than an edge; the previous ray may have passed beside that sheet). So within
    // `farther_hit_retry` longest edges of v the search starts from v (as cheap there), and
    // beyond, a hit that jumped away from the previous one is searched for from v too; the
    // nearer admissible hit wins.
    const double margin = ctx_.options.search_limits.farther_hit_retry * longest_edge_at(v);
    const std::optional<double> previous = mu;
    if (mu && ctx_.rank(*mu) > margin) {
      const double previous_mu = *mu;
      hit = cast_ray(v, ctx_.s1.vertex(v) + previous_mu * direction, *mu, &nearest);
      if (hit && ctx_.rank(*mu) > ctx_.rank(previous_mu) + margin) {
        double near_mu = 0.0;
        if (auto near = cast_ray(v, ctx_.s1.vertex(v), near_mu, nullptr); near && ctx_.rank(near_mu) < ctx_.rank(*mu)) {
          hit = near;
          *mu = near_mu;
        }
      }
    }
    if (!hit) hit = cast_ray(v, ctx_.s1.vertex(v), mu.emplace(), nullptr);
    // near S2, the seeds from v came first; the previous hit's may still reach a hit they miss
    // (the elements nearest to v lie on another part of S2 whose walks end at its boundary)
    if (!hit && previous && ctx_.rank(*previous) <= margin)
      hit = cast_ray(v, ctx_.s1.vertex(v) + *previous * direction, *mu, &nearest);
    if (!hit) mu.reset();
    return hit;
  }

  /// The longest S1 edge at vertex v (d = 1: segment).
  double longest_edge_at(Index v) const {
    double longest = 0.0;
    for (Index t : ctx_.s1.vertex_elements(v))
      for (int k = 0; k <= d; ++k) longest = std::max(longest, (ctx_.s1.corner(t, k) - ctx_.s1.vertex(v)).norm());
    return longest;
  }

  /// The ray from S1 vertex v against S2, walking from the elements of S2 nearest to
  /// `seed_point`; `hit_mu` receives the ray parameter of the hit.
  std::optional<SurfacePoint<d>> cast_ray(Index v, const WorldPoint<d>& seed_point, double& hit_mu,
                                          NearestElements<d>* nearest) {
    const WorldPoint<d>& origin = ctx_.s1.vertex(v);
    const WorldPoint<d>& direction = ctx_.vertex_directions[v];
    // an isolated S1 vertex (no element) is not part of S1: no ghost node, whatever its direction
    if (direction.squaredNorm() == 0.0 || ctx_.s1.vertex_elements(v).empty()) return std::nullopt;
    SeedElements seeds;
    const int count = nearest_seeds(*ctx_.s2_index, nearest, seed_point, ctx_.seed_count, seeds);
    std::optional<SurfacePoint<d>> best;
    double best_rank = std::numeric_limits<double>::infinity();
    // The ray against S2 element t: a hit inside t that is admissible and nearer than the best
    // so far becomes the best. Returns the corner opposite the side to walk across towards the
    // ray's point, or -1 once the ray's point lies in t (or the ray runs parallel to t).
    auto test_element = [&](Index t) -> int {
      // origin + mu direction = c0 + sum_i y_i (c_{i+1} - c0): linear in (y, mu)
      Eigen::Matrix<double, d + 1, d + 1> a;
      double scale = 0.0;
      for (int i = 0; i < d; ++i) {
        a.col(i) = ctx_.s2.corner(t, i + 1) - ctx_.s2.corner(t, 0);
        scale = std::max(scale, a.col(i).norm());
      }
      a.col(d) = -direction;
      const double det = a.determinant();
      if (!(std::abs(det) > 1e-12 * integer_power(scale, d))) return -1;  // ray parallel to the element
      const Eigen::Matrix<double, d + 1, 1> x = solve_with_partial_pivoting<d + 1>(a, origin - ctx_.s2.corner(t, 0));
      const LocalPoint<d> y = x.template head<d>();
      const Barycentric<d> b = barycentric_from_local<d>(y);
      int worst = 0;
      for (int k = 1; k <= d; ++k)
        if (b(k) < b(worst)) worst = k;
      if (b(worst) < -ctx_.options.search_limits.inside_tolerance) return worst;
      const double mu = x(d);
      WorldPoint<d> target_normal = ctx_.s2.element_normal(t);
      if (!ctx_.distance_ok(mu, scale) && std::isnan(outside_band_)) outside_band_ = static_cast<float>(mu);
      if (ctx_.distance_ok(mu, scale) && ctx_.normal_ok(direction, target_normal) && ctx_.rank(mu) < best_rank &&
          ctx_.ghost_ray_unfolded(v, mu)) {
        best_rank = ctx_.rank(mu);
        hit_mu = mu;
        Barycentric<d> bc = b.cwiseMax(0.0);
        bc /= bc.sum();
        best = SurfacePoint<d>{t, local_from_barycentric<d>(bc)};
      }
      return -1;
    };
    std::array<Index, 64> visited;
    int nvisited = 0;
    for (int s = 0; s < count; ++s) {
      Index t = static_cast<Index>(seeds[s]);
      for (int step = 0; step < ctx_.options.search_limits.seed_walk_steps && t != invalid_index; ++step) {
        if (std::find(visited.begin(), visited.begin() + nvisited, t) != visited.begin() + nvisited) break;
        if (nvisited < 64) visited[nvisited++] = t;
        const int across = test_element(t);
        if (across < 0) break;
        t = element_across(ctx_.s2, t, across);
      }
    }
    // On a curve, a branch of S2 that passes right by v can hold a nearer hit while every seed
    // lies on another branch: a long segment of v's own branch has its centroid far off, and the
    // walks from the seeds stay on their branch (ProjectProperties.RemeshedPolylines…, seed 52:
    // the hit taken 0.11 away on another branch, its own segment's at 0). Where the hit found is
    // farther along the ray than the nearest seed's centroid is from v, every segment whose
    // centroid lies within that reach (plus S2's largest centroid-to-corner distance) is tested.
    // On the concentric circles the hit is never farther than the nearest centroid.
    if constexpr (d == 1) {
      if (best && count > 0 && seed_point == origin) {
        double nearest_centroid = std::numeric_limits<double>::infinity();
        for (int s = 0; s < count; ++s)
          nearest_centroid = std::min(nearest_centroid, (ctx_.s2_index->cloud.points[seeds[s]] - origin).norm());
        const double reach = ctx_.rank(hit_mu) * direction.norm();
        if (reach > nearest_centroid)
          for (const Index t : ctx_.s2_index->within(origin, reach + ctx_.s2_index->radius)) test_element(t);
      }
    }
    return best;
  }

  /// For the last vertex cast: the distance of the first hit found outside the band of
  /// admissible distances, or NaN.
  float outside_band() const { return outside_band_; }

 private:
  const ProjectionContext<d>& ctx_;
  float outside_band_ = std::numeric_limits<float>::quiet_NaN();
};

}  // namespace

template <int d>
std::vector<std::optional<SurfacePoint<d>>> cast_rays_from_s1_vertices(const ProjectionContext<d>& ctx,
                                                                      std::vector<float>* outside_band) {
  const Index n1v = ctx.s1.vertex_count();
  std::vector<std::optional<SurfacePoint<d>>> hit;
  assign_on_huge_pages(hit, static_cast<std::size_t>(n1v), {}, ctx.threads);
  if (outside_band) outside_band->assign(static_cast<std::size_t>(n1v), std::numeric_limits<float>::quiet_NaN());
  parallel_for_chunks(n1v, search_chunk, ctx.threads, [&](Index begin, Index end) {
    GhostRays<d> rays(ctx);
    std::optional<double> mu;  // ray parameter of the previous hit
    NearestElements<d> nearest(*ctx.s2_index);
    for (Index v = begin; v < end; ++v) {
      hit[v] = rays.cast_ray(v, mu, nearest);
      if (outside_band && !hit[v]) (*outside_band)[v] = rays.outside_band();
    }
  });
  return hit;
}

template std::vector<std::optional<SurfacePoint<1>>> cast_rays_from_s1_vertices<1>(const ProjectionContext<1>&,
                                                                                 std::vector<float>*);
template std::vector<std::optional<SurfacePoint<2>>> cast_rays_from_s1_vertices<2>(const ProjectionContext<2>&,
                                                                                 std::vector<float>*);

}  // namespace plmap::projection
