// EditableMap's deferred cut (EditOptions::defer_cut): with it, the editing steps only relocate
// the S2 vertex preimages and never cut an S2 edge's polyline; to_map() traces every S2 edge
// here, once, on the final S1.
//
// Each S2 edge becomes the straight segment between its ends' preimages: inside one S1 triangle
// if a triangle holds both ends; otherwise along a corridor of S1 triangles, each unfolded
// across the edge it shares with the previous one into the plane of the first, found by a
// search that keeps the cone of directions from the first end through every crossed edge (a
// straight line from the start through all the corridor's edges) and stops where the cone
// holds the other end. Of several corridors the shortest segment wins (a geodesic-like choice
// near cone vertices). Then the traced graph must be an embedding with S2's combinatorics:
// inside every S1 triangle no two pieces cross, touch or come within the clearance (the test
// of the per-step cut), and around every vertex preimage the S2 edges leave in S2's rotation
// order. Anything else throws DeferredCutFailure, and the caller redoes the run with the
// per-step cut. See docs/algorithms/simplification.md, "The deferred cut".

#include "editable_map_state.hpp"
#include "piece_clearance.hpp"

#include <plmap/core/predicates.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap {

namespace {

using Vec2 = Eigen::Vector2d;
using detail::pieces_leave_too_close;
using detail::within_margin;
using Vec3 = Eigen::Vector3d;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A straight piece of a traced S2 edge inside one S1 triangle, in that triangle's frame.
struct Piece {
  Index triangle;
  Vec2 from, to;
  Index edge;  ///< the S2 edge
};

/// The tracing, on the state of an EditableMap (a template only so that it can name the state,
/// a private type of EditableMap).
template <class State>
class Tracer {
 public:
  explicit Tracer(const State& s) : s_(s), t2_(*s.target), clearance_(s.options.edge_clearance) {
    frames_.resize(s.triangles.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      if (s.triangle_live[t]) frames_[t] = frame_of(static_cast<Index>(t));
  }

  std::vector<std::vector<TracedCrossing>> run() {
    const Index edge_count = t2_.edge_count();
    std::vector<std::vector<TracedCrossing>> crossings(static_cast<std::size_t>(edge_count));
    end_triangle_.assign(static_cast<std::size_t>(edge_count), {invalid_index, invalid_index});
    end_direction_.assign(static_cast<std::size_t>(edge_count), {Vec2::Zero(), Vec2::Zero()});
    for (Index e = 0; e < edge_count; ++e) trace(e, crossings[static_cast<std::size_t>(e)]);
    check_pieces();
    for (Index w = 0; w < t2_.vertex_count(); ++w) check_rotation(w);
    return crossings;
  }

 private:
  // ---- S1 triangles, their frames, and where the S2 vertex preimages lie in them ----

  /// The planar frame of S1 triangle t: corner 0 at the origin, corner 1 on the positive x axis,
  /// corner 2 above it (so counter-clockwise in the frame is the triangle's orientation).
  std::array<Vec2, 3> frame_of(Index t) const {
    const auto& c = s_.triangles[t];
    const Vec3 a = pos(c[0]), b = pos(c[1]), d = pos(c[2]);
    const double length = (b - a).norm();
    const Vec3 x = (b - a) / length;
    const double dx = (d - a).dot(x);
    const double dy = (d - a - dx * x).norm();
    return {Vec2::Zero(), Vec2(length, 0.0), Vec2(dx, dy)};
  }
  const Vec3& pos(Index v) const { return s_.target->vertex(v); }
  int corner(Index t, Index v) const {
    const auto& c = s_.triangles[t];
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : -1;
  }
  bool is_corner_preimage(Index w) const { return s_.vertex_live[w] != 0; }

  /// True if the closed S1 triangle t holds the preimage of S2 vertex w.
  bool holds(Index t, Index w) const {
    if (is_corner_preimage(w)) return corner(t, w) >= 0;
    if (s_.on_edge(w)) return corner(t, s_.preimage_edge[w][0]) >= 0 && corner(t, s_.preimage_edge[w][1]) >= 0;
    return s_.preimage_triangle[w] == t;
  }
  /// The preimage of w as a combination of t's corners, given their positions (t must hold it).
  Vec2 place(Index t, Index w, const std::array<Vec2, 3>& corners) const {
    if (is_corner_preimage(w)) return corners[corner(t, w)];
    if (s_.on_edge(w)) {
      const auto& e = s_.preimage_edge[w];
      const double u = s_.preimage_edge_parameter[w];
      return (1.0 - u) * corners[corner(t, e[0])] + u * corners[corner(t, e[1])];
    }
    const Vec3& b = s_.preimage_barycentric[w];
    return b(0) * corners[0] + b(1) * corners[1] + b(2) * corners[2];
  }
  /// The point of S1 edge e (smaller vertex first) at parameter u, in t's frame.
  Vec2 on_edge(Index t, const std::array<Index, 2>& e, double u) const {
    return (1.0 - u) * frames_[t][corner(t, e[0])] + u * frames_[t][corner(t, e[1])];
  }
  Vec3 world(Index w) const {
    if (is_corner_preimage(w)) return pos(w);
    if (s_.on_edge(w)) {
      const double u = s_.preimage_edge_parameter[w];
      return (1.0 - u) * pos(s_.preimage_edge[w][0]) + u * pos(s_.preimage_edge[w][1]);
    }
    const auto& c = s_.triangles[s_.preimage_triangle[w]];
    const Vec3& b = s_.preimage_barycentric[w];
    return b(0) * pos(c[0]) + b(1) * pos(c[1]) + b(2) * pos(c[2]);
  }
  /// The live S1 triangles that hold the preimage of w.
  void triangles_holding(Index w, std::vector<Index>& out) const {
    out.clear();
    if (is_corner_preimage(w)) {
      out.assign(s_.vertex_triangles[w].begin(), s_.vertex_triangles[w].end());
    } else if (s_.on_edge(w)) {
      for (Index t : s_.vertex_triangles[s_.preimage_edge[w][0]])
        if (corner(t, s_.preimage_edge[w][1]) >= 0) out.push_back(t);
    } else {
      out.push_back(s_.preimage_triangle[w]);
    }
  }
  /// The S1 triangle across edge (u, v) from t, if exactly one (not a boundary or non-manifold edge).
  Index across(Index t, Index u, Index v) const {
    Index other = invalid_index;
    for (Index n : s_.vertex_triangles[u])
      if (n != t && corner(n, v) >= 0) {
        if (other != invalid_index) return invalid_index;
        other = n;
      }
    return other;
  }

  // ---- one S2 edge ----

  [[noreturn]] void fail(const std::string& why) const { throw DeferredCutFailure("deferred cut: " + why); }

  void trace(Index e, std::vector<TracedCrossing>& out) {
    const auto [a, b] = t2_.edge_vertices(e);
    triangles_holding(a, from_);
    triangles_holding(b, to_);
    // One triangle holds both ends: the segment lies in it (along an S1 edge if both ends are on
    // it; then it belongs to every triangle of that edge).
    bool common = false;
    for (Index t : from_)
      if (std::find(to_.begin(), to_.end(), t) != to_.end()) {
        const Vec2 p = place(t, a, frames_[t]), q = place(t, b, frames_[t]);
        pieces_.push_back({t, p, q, e});
        if (!common) {
          end_triangle_[e] = {t, t};
          end_direction_[e] = {q - p, p - q};
        }
        common = true;
      }
    if (common) return;

    // A corridor: the shortest straight segment from a's preimage to b's over all start triangles.
    const double chord = (world(a) - world(b)).norm();
    // Within a disk of radius 1.25 times the chord first (the S1 path of a short S2 edge is
    // about its chord), then 4 times: the search explores every cone that reaches the disk.
    found_ = false;
    budget_ = 20000;
    for (double factor : {1.25, 4.0}) {
      best_length_ = factor * chord;
      for (Index t0 : from_) {
        apex_ = place(t0, a, frames_[t0]);
        target_ = b;
        path_.assign(1, t0);
        portals_.clear();
        portal_ends_.clear();
        const auto& c = s_.triangles[t0];
        for (int k = 0; k < 3; ++k) {
          const Index x = c[k], y = c[(k + 1) % 3];
          if (is_corner_preimage(a) && (x == a || y == a)) continue;
          if (!is_corner_preimage(a) && s_.on_edge(a) && sorted_pair(x, y) == s_.preimage_edge[a]) continue;
          enter(t0, frames_[t0], x, y, nullptr, nullptr);
        }
      }
      if (found_) break;
    }
    if (budget_ < 0) fail(fmt::format("the search for S2 edge {}'s corridor ran out of budget", e));
    if (!found_) fail(fmt::format("no straight trace of S2 edge {} (vertices {} and {})", e, a, b));

    // Crossings along the best corridor, in order from a, each strictly inside its S1 edge.
    const Vec2 r = best_end_ - best_apex_;
    double previous = 0.0;
    Vec2 from = place(best_path_[0], a, frames_[best_path_[0]]);
    for (std::size_t i = 0; i < best_portals_.size(); ++i) {
      const auto [u, v] = best_portals_[i];
      const Vec2 &pu = best_portal_ends_[i][0], &pv = best_portal_ends_[i][1];
      const Vec2 w = pv - pu;
      const double denominator = cross2(r, w);
      const double along = cross2(pu - best_apex_, w) / denominator;
      const double mu = cross2(best_apex_ - pu, r) / cross2(w, r);
      if (!(along > previous && along < 1.0 && mu > clearance_ && mu < 1.0 - clearance_))
        fail(fmt::format("S2 edge {}'s trace passes too near an S1 vertex", e));
      previous = along;
      const std::array<Index, 2> key = sorted_pair(u, v);
      const double edge_parameter = u < v ? mu : 1.0 - mu;
      out.push_back({key, edge_parameter, along});
      const Index t = best_path_[i];
      const Vec2 to = on_edge(t, key, edge_parameter);
      if (i == 0) {
        end_triangle_[e][0] = t;
        end_direction_[e][0] = to - from;
      }
      pieces_.push_back({t, from, to, e});
      from = on_edge(best_path_[i + 1], key, edge_parameter);
    }
    const Index last = best_path_.back();
    const Vec2 end = place(last, b, frames_[last]);
    pieces_.push_back({last, from, end, e});
    end_triangle_[e][1] = last;
    end_direction_[e][1] = from - end;
  }

  /// Crosses from triangle t (corners at `corners` in the unfolding) over its edge (x, y) into
  /// the triangle beyond, keeping the cone of directions from the apex between the rays through
  /// `right` and `left` (null: the crossed edge itself bounds it).
  void enter(Index t, const std::array<Vec2, 3>& corners, Index x, Index y, const Vec2* right, const Vec2* left) {
    if (--budget_ < 0) return;
    Vec2 px = corners[corner(t, x)], py = corners[corner(t, y)];
    const int side = orient2d(apex_, px, py);
    if (side == 0) return;
    if (side < 0) {
      std::swap(px, py);
      std::swap(x, y);
    }
    // px is on the right, py on the left, seen from the apex. Too far: no shorter trace beyond.
    if (std::sqrt(segment_distance2(apex_, px, py)) >= best_length_) return;
    const Vec2 new_right = !right || orient2d(apex_, *right, px) > 0 ? px : *right;
    const Vec2 new_left = !left || orient2d(apex_, py, *left) > 0 ? py : *left;
    if (orient2d(apex_, new_right, new_left) <= 0) return;
    const Index n = across(t, x, y);
    if (n == invalid_index || std::find(path_.begin(), path_.end(), n) != path_.end()) return;
    // Unfold n: its third corner on the other side of (x, y) from t's.
    const auto& c = s_.triangles[n];
    const int kr = 3 - corner(n, x) - corner(n, y);
    const Index r = c[kr];
    const Vec3 d = pos(y) - pos(x);
    const double length = d.norm();
    const double along = (pos(r) - pos(x)).dot(d) / length;
    const double height = (pos(r) - pos(x)).cross(d).norm() / length;
    const Vec2 unit = (py - px).normalized();
    const Vec2 normal(unit.y(), -unit.x());  // to the right of x -> y: away from the apex's side
    std::array<Vec2, 3> next;
    next[corner(n, x)] = px;
    next[corner(n, y)] = py;
    next[kr] = px + along * unit + height * normal;
    path_.push_back(n);
    portals_.push_back({x, y});
    portal_ends_.push_back({px, py});
    if (holds(n, target_)) {
      const Vec2 q = place(n, target_, next);
      const double length_to = (q - apex_).norm();
      if (orient2d(apex_, new_right, q) > 0 && orient2d(apex_, q, new_left) > 0 && length_to < best_length_) {
        best_length_ = length_to;
        found_ = true;
        best_apex_ = apex_;
        best_end_ = q;
        best_path_ = path_;
        best_portals_ = portals_;
        best_portal_ends_ = portal_ends_;
      }
    }
    enter(n, next, x, r, &new_right, &new_left);
    enter(n, next, r, y, &new_right, &new_left);
    path_.pop_back();
    portals_.pop_back();
    portal_ends_.pop_back();
  }

  static double segment_distance2(const Vec2& x, const Vec2& a, const Vec2& b) {
    const Vec2 d = b - a;
    const double length2 = d.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((x - a).dot(d) / length2, 0.0, 1.0) : 0.0;
    return (x - (a + t * d)).squaredNorm();
  }

  // ---- the checks of the traced graph ----

  /// Inside every S1 triangle, pieces must not cross, touch (other than at a shared end) or come
  /// within the clearance times the triangle's size: the per-step cut's test, by a sweep along x.
  void check_pieces() {
    auto min_x = [](const Piece& p) { return std::min(p.from.x(), p.to.x()); };
    std::sort(pieces_.begin(), pieces_.end(), [&min_x](const Piece& a, const Piece& b) {
      return a.triangle != b.triangle ? a.triangle < b.triangle : min_x(a) < min_x(b);
    });
    for (std::size_t a = 0; a < pieces_.size(); ++a) {
      const auto& f = frames_[pieces_[a].triangle];
      const double margin = clearance_ * std::max({f[1].x(), std::abs(f[2].x()), f[2].y()});
      const double max_x = std::max(pieces_[a].from.x(), pieces_[a].to.x()) + margin;
      const double low_y = std::min(pieces_[a].from.y(), pieces_[a].to.y()) - margin;
      const double high_y = std::max(pieces_[a].from.y(), pieces_[a].to.y()) + margin;
      for (std::size_t b = a + 1; b < pieces_.size() && pieces_[b].triangle == pieces_[a].triangle; ++b) {
        if (min_x(pieces_[b]) > max_x) break;
        if (std::max(pieces_[b].from.y(), pieces_[b].to.y()) < low_y ||
            std::min(pieces_[b].from.y(), pieces_[b].to.y()) > high_y)
          continue;
        const Vec2 &p = pieces_[a].from, &q = pieces_[a].to, &r = pieces_[b].from, &t = pieces_[b].to;
        if (p == r || p == t || q == r || q == t) {
          const Vec2& shared = (p == r || p == t) ? p : q;
          const Vec2& end_a = shared == p ? q : p;
          const Vec2& end_b = r == shared ? t : r;
          if (orient2d(shared, end_a, end_b) != 0) {
            if (!pieces_leave_too_close(end_a - shared, end_b - shared, margin)) continue;
            fail(fmt::format("two traced pieces leave one node too close together in S1 triangle {}", pieces_[a].triangle));
          }
        } else if (within_margin(p, r, t, margin) || within_margin(q, r, t, margin) || within_margin(r, p, q, margin) ||
                   within_margin(t, p, q, margin)) {
          fail(fmt::format("two traced pieces come within the clearance in S1 triangle {}", pieces_[a].triangle));
        }
        if (segments_cross_properly(p, q, r, t))
          fail(fmt::format("the traces of S2 edges {} and {} cross in S1 triangle {}", pieces_[a].edge, pieces_[b].edge,
                           pieces_[a].triangle));
      }
    }
  }

  /// The S2 edges at w must leave its preimage in S2's counter-clockwise order around w. Checked
  /// where both orders are one cycle: w's S2 star is a closed fan, and its preimage is inside an
  /// S1 triangle or an S1 vertex with a closed fan (preimages on S1 edges lie on feature lines,
  /// whose S2 edges run along S1 edges).
  void check_rotation(Index w) {
    // S2's ring around w, counter-clockwise.
    ring_.clear();
    next_.clear();
    for (Index t : t2_.vertex_elements(w)) {
      const auto& c = t2_.element(t);
      const int k = t2_.local_corner(t, w);
      next_.push_back({c[(k + 1) % 3], c[(k + 2) % 3]});
    }
    if (next_.size() < 3) return;
    Index current = next_.front()[0];
    for (std::size_t step = 0; step < next_.size(); ++step) {
      ring_.push_back(current);
      Index following = invalid_index;
      int count = 0;
      for (const auto& n : next_)
        if (n[0] == current) {
          following = n[1];
          ++count;
        }
      if (count != 1) return;
      current = following;
    }
    if (current != ring_.front()) return;

    // The angle of each S2 edge where it leaves w's preimage.
    angles_.clear();
    if (is_corner_preimage(w)) {
      if (!s1_fan_angles(w)) return;
    } else if (s_.on_edge(w)) {
      return;
    }
    for (Index x : ring_) {
      const Index e = t2_.find_edge(w, x);
      const int end = t2_.edge_vertices(e)[0] == w ? 0 : 1;
      const Index t = end_triangle_[e][end];
      const Vec2& d = end_direction_[e][end];
      double angle = 0.0;
      if (is_corner_preimage(w)) {
        const auto& c = s_.triangles[t];
        const int k = corner(t, w);
        const Vec2 spoke = frames_[t][(k + 1) % 3] - frames_[t][k];
        const auto at = std::find(fan_triangles_.begin(), fan_triangles_.end(), t);
        if (at == fan_triangles_.end()) fail(fmt::format("S2 vertex {}'s edge {} leaves from outside its fan", w, e));
        angle = fan_offsets_[static_cast<std::size_t>(at - fan_triangles_.begin())] +
                std::atan2(cross2(spoke, d), spoke.dot(d));
        (void)c;
      } else {
        angle = std::atan2(d.y(), d.x());
      }
      angles_.push_back({angle, x});
    }
    std::sort(angles_.begin(), angles_.end());
    std::size_t start = 0;
    while (start < angles_.size() && angles_[start].second != ring_.front()) ++start;
    for (std::size_t i = 0; i < ring_.size(); ++i)
      if (angles_[(start + i) % angles_.size()].second != ring_[i])
        fail(fmt::format("the S2 edges around S2 vertex {} leave its preimage out of S2's order", w));
  }

  /// The S1 triangles around S1 vertex w in counter-clockwise order with the angle at w before
  /// each; false if they are not one closed fan.
  bool s1_fan_angles(Index w) {
    fan_triangles_.clear();
    fan_offsets_.clear();
    const auto& star = s_.vertex_triangles[w];
    if (star.size() < 3) return false;
    Index t = star.front();
    double offset = 0.0;
    for (std::size_t step = 0; step < star.size(); ++step) {
      fan_triangles_.push_back(t);
      fan_offsets_.push_back(offset);
      const auto& c = s_.triangles[t];
      const int k = corner(t, w);
      const Vec2 u = frames_[t][(k + 1) % 3] - frames_[t][k], v = frames_[t][(k + 2) % 3] - frames_[t][k];
      offset += std::atan2(cross2(u, v), u.dot(v));
      const Index y = c[(k + 2) % 3];
      Index following = invalid_index;
      int count = 0;
      for (Index n : star) {
        const int m = corner(n, w);
        if (s_.triangles[n][(m + 1) % 3] == y) {
          following = n;
          ++count;
        }
      }
      if (count != 1) return false;
      t = following;
    }
    return t == star.front();
  }

  const State& s_;
  const Surface<2>& t2_;
  double clearance_;
  std::vector<std::array<Vec2, 3>> frames_;  ///< per S1 triangle slot (live ones)
  std::vector<Piece> pieces_;
  std::vector<std::array<Index, 2>> end_triangle_;  ///< per S2 edge: the S1 triangle its trace leaves each end in
  std::vector<std::array<Vec2, 2>> end_direction_;  ///< ... and the direction, in that triangle's frame
  // The corridor search of the current edge.
  std::vector<Index> from_, to_;
  Vec2 apex_;
  Index target_ = invalid_index;
  std::vector<Index> path_;
  std::vector<std::array<Index, 2>> portals_;
  std::vector<std::array<Vec2, 2>> portal_ends_;
  double best_length_ = 0.0;
  bool found_ = false;
  int budget_ = 0;
  Vec2 best_apex_, best_end_;
  std::vector<Index> best_path_;
  std::vector<std::array<Index, 2>> best_portals_;
  std::vector<std::array<Vec2, 2>> best_portal_ends_;
  // The rotation check.
  std::vector<Index> ring_;
  std::vector<std::array<Index, 2>> next_;
  std::vector<std::pair<double, Index>> angles_;
  std::vector<Index> fan_triangles_;
  std::vector<double> fan_offsets_;
};

}  // namespace

std::vector<std::vector<TracedCrossing>> EditableMap::Trace::run(const Impl& s) { return Tracer<Impl>(s).run(); }

}  // namespace plmap
