// Overlay maps: Xi = identity of the plane between two triangulations of one planar domain, or
// between two subdivisions of one polyline (see random_maps.hpp).
//
// Every combinatorial decision (is this point on that edge, does this edge cross that one) is an
// exact orientation test on the input doubles; only the positions of intersection points are
// computed in floating point.

#include <plmap/core/errors.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace plmap::generators {

namespace {

Eigen::Vector2d xy(const WorldPoint<2>& p) { return p.head<2>(); }

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Local coordinates of the point at parameter u along local edge k (from corner k to k+1).
LocalPoint<2> local_on_edge(int k, double u) {
  switch (k) {
    case 0: return {u, 0.0};
    case 1: return {1.0 - u, u};
    default: return {0.0, 1.0 - u};
  }
}

void require_planar_ccw(const Surface<2>& s, const char* which) {
  for (Index v = 0; v < s.vertex_count(); ++v)
    if (s.vertex(v).z() != 0.0 && !s.vertex_elements(v).empty())  // isolated vertices do not count
      throw Error(fmt::format("plane overlay: {} vertex {} is not in the plane z = 0", which, v));
  for (Index t = 0; t < s.element_count(); ++t)
    if (orient2d(xy(s.corner(t, 0)), xy(s.corner(t, 1)), xy(s.corner(t, 2))) <= 0)
      throw Error(fmt::format("plane overlay: {} element {} is not counter-clockwise", which, t));
}

/// Where point p of the plane lies on the planar surface s (first containing element, found with
/// exact predicates). Barycentric coordinates within `snap` of zero count as zero, the rule
/// MapBuilder applies, so that the generator and the builder agree on vertices and edges.
DomainLocation<2> locate_in_plane(const Surface<2>& s, const Eigen::Vector2d& p, const char* which,
                                  double snap) {
  using Kind = DomainLocation<2>::Kind;
  for (Index t = 0; t < s.element_count(); ++t) {
    const std::array<Eigen::Vector2d, 3> c{xy(s.corner(t, 0)), xy(s.corner(t, 1)), xy(s.corner(t, 2))};
    std::array<int, 3> side{};  // side[k]: orientation of p against local edge k
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      side[k] = orient2d(c[k], c[(k + 1) % 3], p);
      inside = side[k] >= 0;
    }
    if (!inside) continue;
    // Barycentric coordinates by Cramer's rule; corner (k + 2) % 3 is opposite local edge k.
    const Eigen::Vector2d e1 = c[1] - c[0], e2 = c[2] - c[0], q = p - c[0];
    const double det = cross(e1, e2);
    const double xi0 = cross(q, e2) / det, xi1 = cross(e1, q) / det;
    std::array<double, 3> b{1.0 - xi0 - xi1, xi0, xi1};
    std::array<bool, 3> on_edge{};
    for (int k = 0; k < 3; ++k) {
      on_edge[k] = side[k] == 0 || b[(k + 2) % 3] <= snap;
      if (on_edge[k]) b[(k + 2) % 3] = 0.0;
    }
    DomainLocation<2> loc;
    const int zeros = static_cast<int>(std::count(on_edge.begin(), on_edge.end(), true));
    if (zeros >= 2) {
      // On two edges: at their common corner (edge k holds corners k, k+1).
      int corner = 0;
      for (int k = 0; k < 3; ++k)
        if (on_edge[k] && on_edge[(k + 1) % 3]) corner = (k + 1) % 3;
      loc.kind = Kind::vertex;
      loc.index = s.element(t)[corner];
      loc.point = {t, reference_corner<2>(corner)};
    } else if (zeros == 1) {
      const int k = static_cast<int>(std::find(on_edge.begin(), on_edge.end(), true) - on_edge.begin());
      const double u = b[(k + 1) % 3] / (b[k] + b[(k + 1) % 3]);  // from corner k to corner k+1
      loc.kind = Kind::edge;
      loc.index = s.element_edge(t, k);
      loc.edge_parameter = s.local_edge_is_forward(t, k) ? u : 1.0 - u;
      loc.point = {t, local_on_edge(k, u)};
    } else {
      loc.kind = Kind::element;
      loc.index = t;
      loc.point = {t, LocalPoint<2>(b[1], b[2])};
    }
    return loc;
  }
  throw Error(fmt::format("plane overlay: point ({}, {}) is not on {}", p.x(), p.y(), which));
}

/// True if a point placed at `where` (by locate_in_plane) lies on S1 edge f = (a, b): inside it
/// or at one of its ends.
bool placed_on_edge(const DomainLocation<2>& where, Index f, Index a, Index b) {
  using Kind = DomainLocation<2>::Kind;
  return (where.kind == Kind::edge && where.index == f) ||
         (where.kind == Kind::vertex && (where.index == a || where.index == b));
}

}  // namespace

MapCase<2> plane_overlay_map(std::shared_ptr<const Surface<2>> s1, std::shared_ptr<const Surface<2>> s2,
                             std::string description) {
  require_planar_ccw(*s1, "S1");
  require_planar_ccw(*s2, "S2");
  MapBuilder<2> builder(s1, s2);
  const double snap = BuilderOptions{}.snap_tolerance;
  MapCase<2> c;
  c.description = std::move(description);

  // S2 vertices on S1.
  std::vector<Index> s1_vertex_as_s2_vertex(s1->vertex_count(), invalid_index);
  std::vector<DomainLocation<2>> s2_vertex_place(s2->vertex_count());
  for (Index v = 0; v < s2->vertex_count(); ++v) {
    if (s2->vertex_elements(v).empty()) {  // isolated: not part of S2, needs no preimage
      c.target_vertex_preimage.push_back(no_preimage<2>());
      continue;
    }
    const DomainLocation<2> loc = locate_in_plane(*s1, xy(s2->vertex(v)), "S1", snap);
    s2_vertex_place[v] = loc;
    add_vertex_preimage(builder, v, loc);
    c.target_vertex_preimage.push_back(loc.point);
    if (loc.kind == DomainLocation<2>::Kind::vertex) s1_vertex_as_s2_vertex[loc.index] = v;
  }

  // S2 edges: the S1 vertices they pass through and the S1 edges they cross, in order.
  std::vector<std::vector<EdgeCrossing>> crossings(s2->edge_count());
  std::vector<bool> passed(s1->vertex_count(), false);
  for (Index e = 0; e < s2->edge_count(); ++e) {
    // u < v: crossings are listed from u. Not a structured binding: the lambda below captures
    // u and v, which clang 14 (scripts/fuzz) does not allow for bindings.
    const Index u = s2->edge_vertices(e)[0], v = s2->edge_vertices(e)[1];
    const Eigen::Vector2d pu = xy(s2->vertex(u)), pv = xy(s2->vertex(v));
    const Eigen::Vector2d dir = pv - pu;
    std::vector<std::pair<Index, double>> vertex_passes;  // S1 vertex, parameter on e
    auto pass_vertex = [&](Index a) {
      if (s1_vertex_as_s2_vertex[a] == u || s1_vertex_as_s2_vertex[a] == v) return;
      for (const auto& p : vertex_passes)
        if (p.first == a) return;
      vertex_passes.push_back({a, (xy(s1->vertex(a)) - pu).dot(dir) / dir.squaredNorm()});
    };
    // Exactly on the edge (this also covers S2 edges running along S1 edges).
    for (Index a = 0; a < s1->vertex_count(); ++a) {
      if (s1->vertex_elements(a).empty()) continue;  // isolated: not part of S1, nothing to pass
      const Eigen::Vector2d pa = xy(s1->vertex(a));
      if (pa == pu || pa == pv || orient2d(pu, pv, pa) != 0) continue;
      if ((pa - pu).dot(dir) > 0.0 && (pa - pv).dot(-dir) > 0.0) pass_vertex(a);
    }
    for (Index f = 0; f < s1->edge_count(); ++f) {
      const auto [a, b] = s1->edge_vertices(f);
      // Both ends placed on f: e runs along f, so the builder puts its preimage on f and it
      // crosses nothing there. The test matters when e is collinear with f only up to rounding
      // (grid points such as 5/6 and 1/6): the exact predicates below may then report a
      // crossing, and the nearly zero denominator would give it meaningless parameters.
      if (placed_on_edge(s2_vertex_place[u], f, a, b) && placed_on_edge(s2_vertex_place[v], f, a, b)) continue;
      const Eigen::Vector2d pa = xy(s1->vertex(a)), pb = xy(s1->vertex(b));
      if (orient2d(pu, pv, pa) * orient2d(pu, pv, pb) > 0) continue;
      if (orient2d(pa, pb, pu) * orient2d(pa, pb, pv) > 0) continue;
      const Eigen::Vector2d along = pb - pa;
      const double denominator = cross(along, dir);
      if (denominator == 0.0) continue;  // parallel: handled by the exact test above
      const double on_f = cross(pu - pa, dir) / denominator;
      const double on_e = cross(pu - pa, along) / denominator;
      // The builder's snapping rule, applied here too so that both agree on what is a vertex.
      if (on_e <= snap || on_e >= 1.0 - snap) continue;  // at an end of e: its vertex preimage
      if (on_f <= snap) {
        pass_vertex(a);
      } else if (on_f >= 1.0 - snap) {
        pass_vertex(b);
      } else {
        EdgeCrossing x;
        x.domain_edge = f;
        x.domain_parameter = on_f;
        x.target_parameter = on_e;
        crossings[e].push_back(x);
      }
    }
    for (const auto& [a, parameter] : vertex_passes) {
      // Through S1 vertex a: expressed as the end of any S1 edge at a.
      const Index t = s1->vertex_elements(a).front();
      const Index edge = s1->element_edge(t, s1->local_corner(t, a));
      EdgeCrossing x;
      x.domain_edge = edge;
      x.domain_parameter = s1->edge_vertices(edge)[0] == a ? 0.0 : 1.0;
      x.target_parameter = parameter;
      crossings[e].push_back(x);
      passed[a] = true;
    }
    std::sort(crossings[e].begin(), crossings[e].end(),
              [](const EdgeCrossing& x, const EdgeCrossing& y) { return x.target_parameter < y.target_parameter; });
  }

  // The other S1 vertices are ghost nodes. Those that an S2 edge passes are left to the builder:
  // inserting that edge creates the ghost node automatically (paper 3.1), a path worth
  // exercising; the rest are entered with their image on S2.
  for (Index w = 0; w < s1->vertex_count(); ++w) {
    if (s1_vertex_as_s2_vertex[w] != invalid_index || passed[w] || s1->vertex_elements(w).empty()) continue;
    builder.add_ghost_node(w, locate_in_plane(*s2, xy(s1->vertex(w)), "S2", snap).point);
  }
  for (Index e = 0; e < s2->edge_count(); ++e) {
    if (crossings[e].empty())
      builder.add_edge(e);
    else
      builder.add_edge(e, crossings[e]);
  }

  c.map = std::make_shared<const PlMap<2>>(std::move(builder).finalize());
  c.domain = std::move(s1);
  c.target = std::move(s2);
  return c;
}

// ---- d = 1 -------------------------------------------------------------------------------------

Surface<1> subdivide_polyline(const Surface<1>& base, const std::vector<std::vector<double>>& splits) {
  if (splits.size() != static_cast<std::size_t>(base.element_count()))
    throw std::invalid_argument("subdivide_polyline: one split list per segment needed");
  std::vector<WorldPoint<1>> vertices = base.vertices();
  std::vector<ElementCorners<1>> elements;
  for (Index t = 0; t < base.element_count(); ++t) {
    const auto [c0, c1] = base.element(t);
    Index previous = c0;
    for (double s : splits[t]) {
      const auto v = static_cast<Index>(vertices.size());
      // Same formula for S1 and S2: equal parameters give bitwise equal points.
      vertices.push_back((1.0 - s) * base.vertex(c0) + s * base.vertex(c1));
      elements.push_back({previous, v});
      previous = v;
    }
    elements.push_back({previous, c1});
  }
  return Surface<1>(std::move(vertices), std::move(elements));
}

PolylineSubdivisions random_subdivisions(std::shared_ptr<const Surface<1>> base, int max_splits, Rng& rng) {
  PolylineSubdivisions out;
  const Index n = base->element_count();
  out.s1_splits.resize(n);
  out.s2_splits.resize(n);
  auto draw = [&](std::vector<double>& mine, const std::vector<double>& other) {
    const int count = uniform_index(rng, max_splits + 1);
    for (int attempt = 0; attempt < 20 * count && static_cast<int>(mine.size()) < count; ++attempt) {
      // Half dyadic (shared with the other subdivision now and then), half arbitrary.
      const double s = (rng() & 1u) ? (1 + uniform_index(rng, 7)) / 8.0 : uniform_real(rng, 0.05, 0.95);
      auto too_close = [s](double q) { return std::abs(q - s) < 0.03; };
      if (std::any_of(mine.begin(), mine.end(), too_close)) continue;
      // Distinct from the other side's points unless equal: no near-coincidences to snap.
      if (std::any_of(other.begin(), other.end(), [&](double q) { return q != s && too_close(q); }))
        continue;
      mine.push_back(s);
    }
    std::sort(mine.begin(), mine.end());
  };
  for (Index t = 0; t < n; ++t) {
    draw(out.s1_splits[t], {});
    draw(out.s2_splits[t], out.s1_splits[t]);
  }
  out.base = std::move(base);
  return out;
}

MapCase<1> polyline_overlay_map(const PolylineSubdivisions& sub, std::string description) {
  const Surface<1>& base = *sub.base;
  auto s1 = std::make_shared<const Surface<1>>(subdivide_polyline(base, sub.s1_splits));
  auto s2 = std::make_shared<const Surface<1>>(subdivide_polyline(base, sub.s2_splits));

  // Per base segment: parameters 0, splits..., 1 with their vertex ids, and the elements between
  // them, for S1 and S2 (subdivide_polyline numbers vertices and elements in this order).
  struct Chain {
    std::vector<double> parameter;
    std::vector<Index> vertex;
    std::vector<Index> element;
  };
  auto chains = [&](const std::vector<std::vector<double>>& splits) {
    std::vector<Chain> out(base.element_count());
    Index next_vertex = base.vertex_count(), next_element = 0;
    for (Index t = 0; t < base.element_count(); ++t) {
      Chain& ch = out[t];
      ch.parameter.push_back(0.0);
      ch.vertex.push_back(base.element(t)[0]);
      for (double s : splits[t]) {
        ch.parameter.push_back(s);
        ch.vertex.push_back(next_vertex++);
      }
      ch.parameter.push_back(1.0);
      ch.vertex.push_back(base.element(t)[1]);
      for (std::size_t i = 0; i + 1 < ch.parameter.size(); ++i) ch.element.push_back(next_element++);
    }
    return out;
  };
  const std::vector<Chain> c1 = chains(sub.s1_splits), c2 = chains(sub.s2_splits);

  /// Interval i of the chain with parameter[i] <= s < parameter[i+1] (s in [0, 1)).
  auto interval = [](const Chain& ch, double s) {
    return static_cast<std::size_t>(std::upper_bound(ch.parameter.begin(), ch.parameter.end(), s) -
                                     ch.parameter.begin()) - 1;
  };
  auto local_in = [](const Chain& ch, std::size_t i, double s) {
    return (s - ch.parameter[i]) / (ch.parameter[i + 1] - ch.parameter[i]);
  };
  auto point_at_vertex = [](const Surface<1>& s, Index v) {
    const Index t = s.vertex_elements(v).front();
    return SurfacePoint<1>{t, reference_corner<1>(s.local_corner(t, v))};
  };

  MapBuilder<1> builder(s1, s2);
  MapCase<1> c;
  c.description = std::move(description);
  c.target_vertex_preimage.resize(s2->vertex_count());
  // Base vertices are vertices of both.
  for (Index v = 0; v < base.vertex_count(); ++v) {
    if (base.vertex_elements(v).empty()) {  // isolated: not part of either subdivision
      c.target_vertex_preimage[v] = no_preimage<1>();
      continue;
    }
    builder.add_vertex_preimage_at_vertex(v, v);
    c.target_vertex_preimage[v] = point_at_vertex(*s1, v);
  }
  for (Index t = 0; t < base.element_count(); ++t) {
    const Chain &ch1 = c1[t], &ch2 = c2[t];
    // S2 split vertices: on an S1 vertex (same parameter) or inside an S1 segment.
    for (std::size_t j = 1; j + 1 < ch2.parameter.size(); ++j) {
      const double s = ch2.parameter[j];
      const std::size_t i = interval(ch1, s);
      if (ch1.parameter[i] == s) {
        builder.add_vertex_preimage_at_vertex(ch2.vertex[j], ch1.vertex[i]);
        c.target_vertex_preimage[ch2.vertex[j]] = point_at_vertex(*s1, ch1.vertex[i]);
      } else {
        const SurfacePoint<1> p{ch1.element[i], LocalPoint<1>(local_in(ch1, i, s))};
        builder.add_vertex_preimage(ch2.vertex[j], p);
        c.target_vertex_preimage[ch2.vertex[j]] = p;
      }
    }
    // S1 split vertices that are no S2 vertex: ghost nodes inside an S2 segment. Every other
    // one is entered by hand; the rest are created by the builder when the S2 segment passing
    // them is inserted, so both paths of paper 3.1 are exercised.
    for (std::size_t i = 1; i + 1 < ch1.parameter.size(); ++i) {
      const double s = ch1.parameter[i];
      const std::size_t j = interval(ch2, s);
      if (ch2.parameter[j] == s || i % 2 == 0) continue;
      builder.add_ghost_node(ch1.vertex[i], {ch2.element[j], LocalPoint<1>(local_in(ch2, j, s))});
    }
    // S2 segments: the S1 vertices strictly inside, in the segment's direction.
    for (std::size_t j = 0; j + 1 < ch2.parameter.size(); ++j) {
      std::vector<VertexCrossing> crossings;
      for (std::size_t i = 1; i + 1 < ch1.parameter.size(); ++i) {
        const double s = ch1.parameter[i];
        if (s > ch2.parameter[j] && s < ch2.parameter[j + 1])
          crossings.push_back({ch1.vertex[i], local_in(ch2, j, s)});
      }
      builder.add_edge(ch2.element[j], crossings);
    }
  }
  c.map = std::make_shared<const PlMap<1>>(std::move(builder).finalize());
  c.domain = std::move(s1);
  c.target = std::move(s2);
  return c;
}

}  // namespace plmap::generators
