// DESIGN.md §4.6: the images of the regions tile Xi(D) ⊂ S2 — per S2 element they must not
// overlap — and, for a parametrization, cover all of S2.
//
// Image corners of neighbouring regions are computed by different affine maps, so they agree
// only up to rounding; an exact intersection test would flag every pair of neighbours. Overlap
// is therefore measured as the area (length) of the intersection, relative to the smaller piece.
// Only pairs whose bounding boxes meet are clipped (OverlapGrid).

#include "check_context.hpp"

#include <plmap/core/triangle_overlap.hpp>

namespace plmap::detail {

namespace {

using Vec2 = Eigen::Vector2d;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

template <int d>
struct ImagePiece {
  Index region;
  double xmin, xmax, ymin, ymax;
  double measure;
  double boundary;                // length of the boundary (d = 1: 2, the two end points)
  double rounding;                // how far its corners may be off: its map's evaluation rounding
  std::array<Vec2, 3> triangle;  // d = 2 only, counter-clockwise
};

/// "; S2 elements short of it: 3 (0.21 of 0.5), ... (N in all)": the first few elements whose
/// covered local measure falls short of the reference element's, for a parametrization's report.
std::string elements_short_of(const std::vector<double>& covered, double reference_measure, double tol,
                              std::string_view surface) {
  constexpr std::size_t named = 5;
  std::string list;
  std::size_t count = 0;
  for (std::size_t t = 0; t < covered.size(); ++t) {
    if (!(covered[t] < reference_measure * (1.0 - tol))) continue;
    if (count++ < named)
      list += fmt::format("{}{} ({:.3g} of {:g})", list.empty() ? "" : ", ", t, covered[t], reference_measure);
  }
  if (count == 0) return {};
  return fmt::format("; {} elements short of it: {}{}", surface, list,
                     count > named ? fmt::format(" ({} in all)", count) : std::string());
}

}  // namespace

template <int d>
void run_coverage(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& s2 = ctx.s2;
  const Index nt2 = s2.element_count();
  const Index nr = static_cast<Index>(m.region_target.size());
  const double reference_measure = d == 1 ? 1.0 : 0.5;
  const double tol = ctx.options.measure_tolerance;
  const double position_tol = ctx.options.local_tolerance;

  // Regions grouped by their S2 element (counting sort).
  std::vector<Index> begin(nt2 + 1, 0), by_target(nr);
  for (Index r = 0; r < nr; ++r) ++begin[m.region_target[r] + 1];
  for (Index t = 0; t < nt2; ++t) begin[t + 1] += begin[t];
  {
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (Index r = 0; r < nr; ++r) by_target[fill[m.region_target[r]]++] = r;
  }

  double domain_world = 0.0, image_world = 0.0;
  double image_world_rounding = 0.0;  ///< the regions' rounding (below), in S2's measure
  // Per element, the measure its regions (S1) and their images (S2) cover, in local coordinates:
  // a map that is not a parametrization is told where it falls short.
  std::vector<double> domain_local_sum(static_cast<std::size_t>(ctx.s1.element_count()), 0.0);
  std::vector<double> image_local_sum(static_cast<std::size_t>(nt2), 0.0);
  std::vector<ImagePiece<d>> pieces;
  std::vector<Box2> boxes;
  OverlapGrid grid;
  for (Index t2 = 0; t2 < nt2; ++t2) {
    pieces.clear();
    double sum = 0.0;
    // What rounding the region maps' evaluation can add to the sum: each corner off by the
    // map's rounding in each coordinate moves the area by at most the boundary times that.
    double rounding = 0.0;
    for (Index i = begin[t2]; i < begin[t2 + 1]; ++i) {
      const Index r = by_target[i];
      const auto& c = m.region_corners[r];
      ImagePiece<d> piece{};
      piece.region = r;
      std::array<LocalPoint<d>, d + 1> q;
      for (int k = 0; k <= d; ++k) q[k] = apply<d>(m.region_map[r], m.node_position[c[k]]);
      double domain_local;
      if constexpr (d == 1) {
        piece.xmin = std::min(q[0](0), q[1](0));
        piece.xmax = std::max(q[0](0), q[1](0));
        piece.measure = piece.xmax - piece.xmin;
        piece.boundary = 2.0;
        domain_local = std::abs(m.node_position[c[1]](0) - m.node_position[c[0]](0));
      } else {
        const double signed_area = 0.5 * cross(q[1] - q[0], q[2] - q[0]);
        piece.triangle = {q[0], q[1], q[2]};
        if (signed_area < 0) std::swap(piece.triangle[1], piece.triangle[2]);
        piece.measure = std::abs(signed_area);
        piece.boundary = (q[1] - q[0]).norm() + (q[2] - q[1]).norm() + (q[0] - q[2]).norm();
        piece.xmin = std::min({q[0].x(), q[1].x(), q[2].x()});
        piece.xmax = std::max({q[0].x(), q[1].x(), q[2].x()});
        piece.ymin = std::min({q[0].y(), q[1].y(), q[2].y()});
        piece.ymax = std::max({q[0].y(), q[1].y(), q[2].y()});
        domain_local = 0.5 * std::abs(cross(m.node_position[c[1]] - m.node_position[c[0]],
                                            m.node_position[c[2]] - m.node_position[c[0]]));
      }
      piece.rounding = region_map_rounding<d>(m.region_map[r]);
      sum += piece.measure;
      rounding += 2.0 * piece.boundary * piece.rounding;
      image_world += piece.measure / reference_measure * s2.element_measure(t2);
      domain_world += domain_local / reference_measure * ctx.s1.element_measure(ctx.region_element(r));
      domain_local_sum[static_cast<std::size_t>(ctx.region_element(r))] += domain_local;
      if (piece.measure > 0) pieces.push_back(piece);
    }
    image_local_sum[static_cast<std::size_t>(t2)] = sum;
    image_world_rounding += rounding / reference_measure * s2.element_measure(t2);
    if (sum > reference_measure * (1.0 + tol) + rounding)
      sink.add("image_overlap", {invalid_index, invalid_index, invalid_index, t2}, [&] {
        return fmt::format("the images of the {} regions on S2 element {} cover {:.17g} of its "
                           "reference measure {:g}: they overlap",
                           begin[t2 + 1] - begin[t2], t2, sum, reference_measure);
      });

    // Pairwise overlaps: d = 1 by sorting the intervals, d = 2 among triangles whose boxes meet.
    auto check_pair = [&](const ImagePiece<d>& a, const ImagePiece<d>& p) {
      double overlap;
      if constexpr (d == 1)
        overlap = std::min(a.xmax, p.xmax) - std::max(a.xmin, p.xmin);
      else
        overlap = triangle_intersection_area(a.triangle, p.triangle);
      // An overlap counts when it is more than a relative share of the smaller piece and more
      // than corner positions off by local_tolerance, or by the rounding of the two region maps,
      // could explain (a strip that wide along the smaller boundary): image corners of thin
      // regions carry the rounding of the projection, and a sliver's map, stretched 1e6-fold,
      // rounds its own corners by more than local_tolerance.
      const double explained =
          (position_tol + 2.0 * (a.rounding + p.rounding)) * std::min(a.boundary, p.boundary);
      if (overlap > std::max(tol * std::min(a.measure, p.measure), explained))
        sink.add("image_overlap", {ctx.region_element(p.region), invalid_index, p.region, t2}, [&] {
          return fmt::format("the images of regions {} and {} overlap on S2 element {} by {:.3g} "
                             "(their measures {:.3g} and {:.3g}, in local coordinates)",
                             a.region, p.region, t2, overlap, a.measure, p.measure);
        });
    };
    if constexpr (d == 1) {
      std::sort(pieces.begin(), pieces.end(),
                [](const ImagePiece<d>& a, const ImagePiece<d>& b) { return a.xmin < b.xmin; });
      std::size_t furthest = 0;
      for (std::size_t i = 1; i < pieces.size(); ++i) {
        check_pair(pieces[furthest], pieces[i]);
        if (pieces[i].xmax > pieces[furthest].xmax) furthest = i;
      }
    } else {
      boxes.clear();
      for (const auto& p : pieces) boxes.push_back({p.xmin, p.xmax, p.ymin, p.ymax});
      grid.for_each_pair(boxes, [&](std::size_t i, std::size_t j) { check_pair(pieces[i], pieces[j]); });
    }
  }

  if (ctx.options.expect_parametrization) {
    const double s1_measure = ctx.s1.measure(), s2_measure = s2.measure();
    if (std::abs(domain_world - s1_measure) > tol * s1_measure)
      sink.add("not_a_parametrization", {}, [&] {
        return fmt::format("the regions cover {:.17g} of S1's measure {:.17g}{}", domain_world,
                           s1_measure, elements_short_of(domain_local_sum, reference_measure, tol, "S1"));
      });
    if (std::abs(image_world - s2_measure) > tol * s2_measure + image_world_rounding)
      sink.add("not_a_parametrization", {}, [&] {
        return fmt::format("the region images cover {:.17g} of S2's measure {:.17g}{}", image_world,
                           s2_measure, elements_short_of(image_local_sum, reference_measure, tol, "S2"));
      });
  }
}

template void run_coverage(const MapContext<1>&, ViolationSink&);
template void run_coverage(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
