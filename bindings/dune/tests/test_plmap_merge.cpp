// plmap::dune::PlmapMerge against dune-grid-glue's ContactMerge on coupling scenarios in the
// manner of dune-grid-glue's own tests: two structured grids (YaspGrid, bent by GeometryGrid for
// the curved cases) touching along one side, non-matching, in 2-D and 3-D; the interface of the
// second grid shifted sideways and lifted by a gap, or both grids bent into a curved interface.
//
// Both mergers get the same extracted boundary patches (Codim1Extractor) through the Merger base
// class, as GridGlue calls them. Asserted: where ContactMerge's result is complete (the shifted
// flat interfaces) the intersection measure on both sides and the mortar mass matrix agree with
// ContactMerge's to rounding; on the curved interfaces, where ContactMerge leaves a little of
// every element out, plmap covers at least as much on every element and agrees with
// ContactMerge's corners to second order in h; every intersection's corners, mapped through
// their parents on both sides, are one point and its image along the projection direction; and
// GridGlue itself runs with the plmap merger swapped in.

#include <plmap/dune/plmap_merge.hh>

#include <dune/common/fvector.hh>
#include <dune/grid-glue/extractors/codim1extractor.hh>
#include <dune/grid-glue/gridglue.hh>
#include <dune/grid-glue/merging/contactmerge.hh>
#include <dune/grid/geometrygrid.hh>
#include <dune/grid/yaspgrid.hh>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace {

/// The bend of the grids: the coupling coordinate (the last one) is moved by `shift` and, for a
/// curved interface, by amplitude * prod sin(pi x_i) over the other coordinates.
template <int dim>
struct Bend : Dune::AnalyticalCoordFunction<double, dim, dim, Bend<dim>> {
  Dune::FieldVector<double, dim> shift = {};
  double amplitude = 0.0;
  void evaluate(const Dune::FieldVector<double, dim>& x, Dune::FieldVector<double, dim>& y) const {
    y = x;
    y += shift;
    double bump = amplitude;
    for (int i = 0; i + 1 < dim; ++i) bump *= std::sin(std::numbers::pi * x[i]);
    y[dim - 1] += bump;
  }
};

template <int dim>
using HostGrid = Dune::YaspGrid<dim, Dune::EquidistantOffsetCoordinates<double, dim>>;
template <int dim>
using BentGrid = Dune::GeometryGrid<HostGrid<dim>, Bend<dim>>;
template <int dim>
using Extractor = Dune::GridGlue::Codim1Extractor<typename BentGrid<dim>::LeafGridView>;

/// A coupling scenario: grid 0 = [0,1]^dim with n0 cells a side, coupled at its top side (last
/// coordinate 1) to grid 1 = [0,1]^(dim-1) x [1,2] with n1 cells a side at its bottom side.
template <int dim>
struct Scenario {
  int n0 = 4, n1 = 5;
  Dune::FieldVector<double, dim> shift = {};  ///< grid 1 only
  double amplitude = 0.0;                     ///< both grids
  /// How far grid 1 may lie behind grid 0 (ContactMerge's allowedOverlap; for plmap negative
  /// distances down to -overlap, and max_distance = overlap): non-matching polygons of one
  /// curve cross each other.
  double overlap = 0.0;
};

/// The two grids and their extracted interface patches.
template <int dim>
struct Coupling {
  std::unique_ptr<HostGrid<dim>> host0, host1;
  std::unique_ptr<Bend<dim>> bend0, bend1;
  std::unique_ptr<BentGrid<dim>> grid0, grid1;
  std::shared_ptr<Extractor<dim>> patch0, patch1;

  explicit Coupling(const Scenario<dim>& s) {
    Dune::FieldVector<double, dim> lower0(0.0), upper0(1.0), lower1(0.0), upper1(1.0);
    lower1[dim - 1] = 1.0;
    upper1[dim - 1] = 2.0;
    host0 = std::make_unique<HostGrid<dim>>(lower0, upper0, filled<int>(s.n0));
    host1 = std::make_unique<HostGrid<dim>>(lower1, upper1, filled<int>(s.n1));
    bend0 = std::make_unique<Bend<dim>>();
    bend0->amplitude = s.amplitude;
    bend1 = std::make_unique<Bend<dim>>();
    bend1->amplitude = s.amplitude;
    bend1->shift = s.shift;
    grid0 = std::make_unique<BentGrid<dim>>(*host0, *bend0);
    grid1 = std::make_unique<BentGrid<dim>>(*host1, *bend1);
    // YaspGrid numbers the faces of a cube x0-, x0+, x1-, x1+, ...: the top side of grid 0 is face
    // 2 dim - 1 of its top elements, the bottom of grid 1 face 2 dim - 2.
    patch0 = std::make_shared<Extractor<dim>>(
        grid0->leafGridView(), [](const auto&, unsigned face) { return face == 2 * dim - 1; });
    patch1 = std::make_shared<Extractor<dim>>(
        grid1->leafGridView(), [](const auto&, unsigned face) { return face == 2 * dim - 2; });
  }

  template <class T>
  static std::array<T, dim> filled(T value) {
    std::array<T, dim> a;
    a.fill(value);
    return a;
  }
};

/// A patch as the merger receives it.
template <int dimworld>
struct Patch {
  std::vector<Dune::FieldVector<double, dimworld>> coords;
  std::vector<unsigned> corners;
  std::vector<Dune::GeometryType> types;

  Patch() = default;
  template <class E>
  explicit Patch(const E& extractor) {
    extractor.getCoords(coords);
    extractor.getGeometryTypes(types);
    std::vector<typename E::VertexVector> faces;
    extractor.getFaces(faces);
    for (const auto& f : faces) corners.insert(corners.end(), f.begin(), f.end());
  }
  const Dune::FieldVector<double, dimworld>& corner(unsigned element, int k) const {
    return coords[corners[element * dimworld + static_cast<unsigned>(k)]];
  }
  /// World point of local coordinates xi in element e.
  Dune::FieldVector<double, dimworld> world(unsigned e, const Dune::FieldVector<double, dimworld - 1>& xi) const {
    auto x = corner(e, 0);
    for (int i = 0; i + 1 < dimworld; ++i) x.axpy(xi[i], corner(e, i + 1) - corner(e, 0));
    return x;
  }
  double measure(unsigned e) const {
    const auto a = corner(e, 1) - corner(e, 0);
    if constexpr (dimworld == 2) {
      return a.two_norm();
    } else {
      const auto b = corner(e, 2) - corner(e, 0);
      return 0.5 * std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
    }
  }
  /// ContactMerge's nodal normals (the normalised sum of the unit element normals), the field
  /// both mergers project grid 0 along by default.
  std::vector<Dune::FieldVector<double, dimworld>> nodal_normals() const {
    std::vector<Dune::FieldVector<double, dimworld>> n(coords.size(), Dune::FieldVector<double, dimworld>(0.0));
    for (unsigned e = 0; e < types.size(); ++e) {
      const auto a = corner(e, 1) - corner(e, 0);
      Dune::FieldVector<double, dimworld> normal;
      if constexpr (dimworld == 2) {
        normal = {a[1], -a[0]};
      } else {
        const auto b = corner(e, 2) - corner(e, 0);
        normal = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      }
      normal /= normal.two_norm();
      for (int k = 0; k < dimworld; ++k) n[corners[e * dimworld + static_cast<unsigned>(k)]] += normal;
    }
    for (auto& v : n) v /= v.two_norm();
    return n;
  }
};

template <int dimworld>
using MergerBase = Dune::GridGlue::Merger<double, dimworld - 1, dimworld - 1, dimworld>;

template <int dimworld>
void build(MergerBase<dimworld>& merger, const Patch<dimworld>& p0, const Patch<dimworld>& p1) {
  std::ostringstream quiet;  // ContactMerge's StandardMerge reports on std::cout
  auto* old = std::cout.rdbuf(quiet.rdbuf());
  try {
    merger.build(p0.coords, p0.corners, p0.types, p1.coords, p1.corners, p1.types);
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
}

/// What the tests compare between the mergers: the measure of the intersections on grid 0 and
/// their images on grid 1, and the mortar mass matrix M(a, b) = sum over intersections of the
/// integral of phi_a psi_b (P1 hat functions of the grid-0 vertex a and the grid-1 vertex b)
/// over the intersection, with a rule exact for products of two linear functions.
struct Coupled {
  double measure0 = 0.0, measure1 = 0.0;
  std::map<std::pair<unsigned, unsigned>, double> mortar;
  std::size_t intersections = 0;
  /// Per grid-0 element: the measure its intersections cover.
  std::map<unsigned, double> covered0;

};

template <int dimworld>
Coupled coupled(const MergerBase<dimworld>& merger, const Patch<dimworld>& p0, const Patch<dimworld>& p1) {
  constexpr int d = dimworld - 1;
  const auto list = merger.intersectionList();
  Coupled out;
  out.intersections = list->size();
  for (unsigned i = 0; i < list->size(); ++i) {
    const unsigned e0 = list->template parent<0>(i), e1 = list->template parent<1>(i);
    std::array<Dune::FieldVector<double, d>, d + 1> xi0, xi1;
    for (int k = 0; k <= d; ++k) {
      xi0[k] = list->template corner<0>(i, static_cast<unsigned>(k));
      xi1[k] = list->template corner<1>(i, static_cast<unsigned>(k));
    }
    // Measure relative to the parent: |det| of the local corner differences.
    const auto relative = [](const auto& xi) {
      if constexpr (d == 1) {
        return std::abs(xi[1][0] - xi[0][0]);
      } else {
        return std::abs((xi[1][0] - xi[0][0]) * (xi[2][1] - xi[0][1]) - (xi[1][1] - xi[0][1]) * (xi[2][0] - xi[0][0]));
      }
    };
    const double size = relative(xi0) * p0.measure(e0);
    out.measure0 += size;
    out.measure1 += relative(xi1) * p1.measure(e1);
    out.covered0[e0] += size;
    // Hat functions at the intersection's corners: barycentric coordinates in the parents.
    const auto hats = [](const Dune::FieldVector<double, d>& xi) {
      std::array<double, d + 1> h;
      h[0] = 1.0;
      for (int j = 0; j < d; ++j) {
        h[j + 1] = xi[j];
        h[0] -= xi[j];
      }
      return h;
    };
    for (int a = 0; a <= d; ++a)
      for (int b = 0; b <= d; ++b) {
        // integral of f g over a simplex S for linear f, g with corner values f_k, g_k:
        // |S| / ((d+1)(d+2)) * (sum_k f_k g_k + sum_k f_k * sum_k g_k)
        double fg = 0.0, f = 0.0, g = 0.0;
        for (int k = 0; k <= d; ++k) {
          const double fk = hats(xi0[k])[a], gk = hats(xi1[k])[b];
          fg += fk * gk;
          f += fk;
          g += gk;
        }
        const double value = size / ((d + 1) * (d + 2)) * (fg + f * g);
        const unsigned va = p0.corners[e0 * dimworld + static_cast<unsigned>(a)];
        const unsigned vb = p1.corners[e1 * dimworld + static_cast<unsigned>(b)];
        out.mortar[{va, vb}] += value;
      }
  }
  return out;
}

/// Largest difference of two sparse matrices (missing entries are zero).
template <class Key>
double max_difference(const std::map<Key, double>& a, const std::map<Key, double>& b) {
  double worst = 0.0;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    worst = std::max(worst, std::abs(value - (it == b.end() ? 0.0 : it->second)));
  }
  for (const auto& [key, value] : b)
    if (!a.contains(key)) worst = std::max(worst, std::abs(value));
  return worst;
}

template <class Key>
double max_entry(const std::map<Key, double>& a) {
  double m = 0.0;
  for (const auto& entry : a) m = std::max(m, std::abs(entry.second));
  return m;
}

/// Runs both mergers on a scenario.
template <int dim>
struct Comparison {
  Coupling<dim> coupling;
  Patch<dim> p0, p1;
  plmap::dune::PlmapMerge<dim> plmap_merger;
  Dune::GridGlue::ContactMerge<dim, double> contact_merger;
  Coupled plmap_result, contact_result;

  explicit Comparison(const Scenario<dim>& s)
      : coupling(s), p0(*coupling.patch0), p1(*coupling.patch1), contact_merger(s.overlap) {
    if (s.overlap > 0) {
      plmap::dune::PlmapMergeOptions<dim> options;
      options.projection.allow_negative_distance = true;
      options.projection.max_distance = s.overlap;
      plmap_merger.set_options(options);
    }
    build<dim>(plmap_merger, p0, p1);
    build<dim>(contact_merger, p0, p1);
    plmap_result = coupled<dim>(plmap_merger, p0, p1);
    contact_result = coupled<dim>(contact_merger, p0, p1);
    for (unsigned e = 0; e < p0.types.size(); ++e) interface0 += p0.measure(e);
  }
  double interface0 = 0.0;  ///< measure of grid 0's interface

  /// Where ContactMerge is incomplete: plmap covers at least what ContactMerge covers on every
  /// grid-0 element, and each of ContactMerge's intersection corners, a point of grid 0 and its
  /// image on grid 1, is mapped by plmap's map to the same image up to second order in h. Not to
  /// rounding: ContactMerge finds the preimages of grid-1 vertices by a linearisation (its
  /// doInverseProjection: barycentric coordinates with respect to the forward images of the
  /// grid-0 corners), exact only where the direction field is constant, and its pieces of
  /// neighbouring element pairs then leave small gaps (the measure it misses); plmap solves the
  /// projection equation at these points. Returns the number of grid-0 elements where plmap
  /// covers more.
  int expect_plmap_covers_contact_merge(double h, bool compare_corners = true) const {
    int more = 0;
    for (const auto& [e, covered] : contact_result.covered0) {
      const double mine = plmap_result.covered0.contains(e) ? plmap_result.covered0.at(e) : 0.0;
      EXPECT_GE(mine, covered - 1e-12 * p0.measure(e)) << "grid-0 element " << e;
      if (mine > covered + 1e-9 * p0.measure(e)) ++more;
    }
    if (!compare_corners) return more;
    // ContactMerge's linearised corners may lie just outside plmap's exact domain: those are
    // counted, not compared. (With a gap between curved grids, the boundary ring of the
    // interface is full of them; those scenarios compare only the covered measures.)
    const auto theirs = contact_merger.intersectionList();
    std::size_t outside = 0;
    for (unsigned i = 0; i < theirs->size(); ++i)
      for (unsigned k = 0; k < static_cast<unsigned>(dim); ++k) {
        const unsigned e0 = theirs->template parent<0>(i);
        const auto xi0 = theirs->template corner<0>(i, k);
        const auto y = p1.world(theirs->template parent<1>(i), theirs->template corner<1>(i, k));
        const auto image = image_under(plmap_merger, e0, xi0);
        if (!image) {
          ++outside;
          continue;
        }
        EXPECT_LE((*image - y).two_norm(), 0.2 * h * h) << "intersection " << i << " corner " << k;
      }
    EXPECT_LE(outside, theirs->size() * dim / 20) << "ContactMerge's corners outside plmap's domain";
    return more;
  }

  /// The image of (e0, xi0) under the merger's intersections: the one on e0 that contains xi0,
  /// mapped affinely onto its grid-1 parent (a brute-force point location).
  std::optional<Dune::FieldVector<double, dim>> image_under(const MergerBase<dim>& merger, unsigned e0,
                                                             const Dune::FieldVector<double, dim - 1>& xi0) const {
    const auto list = merger.intersectionList();
    for (unsigned i = 0; i < list->size(); ++i) {
      if (list->template parent<0>(i) != e0) continue;
      // barycentric coordinates of xi0 in the intersection's grid-0 corners
      std::array<double, dim> lambda{};
      const auto c0 = list->template corner<0>(i, 0);
      if constexpr (dim == 2) {
        lambda[1] = (xi0[0] - c0[0]) / (list->template corner<0>(i, 1)[0] - c0[0]);
      } else {
        const auto a = list->template corner<0>(i, 1) - c0;
        const auto b = list->template corner<0>(i, 2) - c0;
        const auto p = xi0 - c0;
        const double det = a[0] * b[1] - a[1] * b[0];
        lambda[1] = (p[0] * b[1] - p[1] * b[0]) / det;
        lambda[2] = (a[0] * p[1] - a[1] * p[0]) / det;
      }
      lambda[0] = 1.0 - std::accumulate(lambda.begin() + 1, lambda.end(), 0.0);
      if (*std::min_element(lambda.begin(), lambda.end()) < -1e-9) continue;
      Dune::FieldVector<double, dim - 1> xi1(0.0);
      for (unsigned k = 0; k < static_cast<unsigned>(dim); ++k) xi1.axpy(lambda[k], list->template corner<1>(i, k));
      return p1.world(list->template parent<1>(i), xi1);
    }
    return std::nullopt;
  }

};

/// Every intersection's corner x (through its grid-0 parent) and y (through its grid-1 parent):
/// y - x lies along the interpolated projection direction at x (the normal projection), at a
/// distance at most `max_gap`. Returns the largest distance off that ray, relative to the grid
/// size h, which the caller bounds by a multiple of the rounding unit.
template <int dimworld>
double largest_off_ray(const MergerBase<dimworld>& merger, const Patch<dimworld>& p0, const Patch<dimworld>& p1,
                       double max_gap, double h) {
  constexpr int d = dimworld - 1;
  const auto normals = p0.nodal_normals();
  const auto list = merger.intersectionList();
  double worst = 0.0;
  for (unsigned i = 0; i < list->size(); ++i) {
    const unsigned e0 = list->template parent<0>(i), e1 = list->template parent<1>(i);
    for (unsigned k = 0; k <= d; ++k) {
      const auto xi0 = list->template corner<0>(i, k);
      const auto xi1 = list->template corner<1>(i, k);
      for (int j = 0; j < d; ++j) {
        EXPECT_GE(xi0[j], -1e-12) << "intersection " << i << " corner " << k << " outside its grid-0 parent";
        EXPECT_GE(xi1[j], -1e-12) << "intersection " << i << " corner " << k << " outside its grid-1 parent";
      }
      EXPECT_LE(std::accumulate(xi0.begin(), xi0.end(), 0.0), 1 + 1e-12) << "intersection " << i << " corner " << k;
      EXPECT_LE(std::accumulate(xi1.begin(), xi1.end(), 0.0), 1 + 1e-12) << "intersection " << i << " corner " << k;
      const auto x = p0.world(e0, xi0), y = p1.world(e1, xi1);
      Dune::FieldVector<double, dimworld> direction = normals[p0.corners[e0 * dimworld]];
      direction *= 1.0 - std::accumulate(xi0.begin(), xi0.end(), 0.0);
      for (int j = 0; j < d; ++j) direction.axpy(xi0[j], normals[p0.corners[e0 * dimworld + static_cast<unsigned>(j) + 1]]);
      direction /= direction.two_norm();
      auto w = y - x;
      const double along = w * direction;
      EXPECT_LE(std::abs(along), max_gap * (1 + 1e-9)) << "intersection " << i << " corner " << k;
      w.axpy(-along, direction);
      worst = std::max(worst, w.two_norm() / h);
    }
  }
  return worst;
}

// Tolerances: the quantities are sums of O(number of intersections) terms of size up to 1.
constexpr double rounding = 1e-12;

// --- 2-D grids, 1-D interface ---------------------------------------------------------------

TEST(PlmapMerge2d, ShiftedFlatInterfaceAgreesWithContactMerge) {
  // Grid 1 moved sideways by 0.3 and up by a gap of 0.05: the interface overlaps on [0.3, 1].
  Comparison<2> c(Scenario<2>{.n0 = 5, .n1 = 7, .shift = {0.3, 0.05}, .amplitude = 0.0, .overlap = 0.0});
  EXPECT_NEAR(c.contact_result.measure0, 0.7, rounding);  // ContactMerge's result is complete
  EXPECT_NEAR(c.plmap_result.measure0, 0.7, rounding);
  EXPECT_NEAR(c.plmap_result.measure1, 0.7, rounding);
  EXPECT_LE(max_difference(c.plmap_result.mortar, c.contact_result.mortar), rounding);
  EXPECT_LE(largest_off_ray<2>(c.plmap_merger, c.p0, c.p1, 0.05, 0.2), rounding);
}

TEST(PlmapMerge2d, CurvedInterfaceCoversWhatContactMergeCoversAndMore) {
  // Both grids bent by 0.15 sin(pi x): non-matching polygons of the same curve, which cross.
  Comparison<2> c(Scenario<2>{.n0 = 6, .n1 = 9, .shift = {0.0, 0.0}, .amplitude = 0.15, .overlap = 0.02});
  // plmap covers all of grid 0's interface. ContactMerge is incomplete on every element (it
  // drops a small piece of each, 0.05 to 1 %), so the two are compared piece by piece.
  EXPECT_NEAR(c.plmap_result.measure0, c.interface0, rounding);
  EXPECT_LT(c.contact_result.measure0, c.interface0 * (1 - 1e-4));
  EXPECT_GE(c.expect_plmap_covers_contact_merge(1.0 / 6), 1);
  EXPECT_GT(max_entry(c.plmap_result.mortar), 0.01);
  EXPECT_LE(largest_off_ray<2>(c.plmap_merger, c.p0, c.p1, 0.02, 1.0 / 6), rounding);
}

TEST(PlmapMerge2d, CurvedInterfaceWithGapCoversWhatContactMergeCoversAndMore) {
  Comparison<2> c(Scenario<2>{.n0 = 6, .n1 = 9, .shift = {0.0, 0.05}, .amplitude = 0.15, .overlap = 0.0});
  EXPECT_GT(c.plmap_result.measure0, c.contact_result.measure0);
  EXPECT_GE(c.expect_plmap_covers_contact_merge(1.0 / 6, false), 1);
  EXPECT_LE(largest_off_ray<2>(c.plmap_merger, c.p0, c.p1, 0.1, 1.0 / 6), rounding);
}

// --- 3-D grids, 2-D interface ---------------------------------------------------------------

TEST(PlmapMerge3d, ShiftedFlatInterfaceAgreesWithContactMerge) {
  // Grid 1 moved by (0.25, 0.15) sideways and 0.05 up: the interfaces overlap on
  // [0.25, 1] x [0.15, 1], area 0.75 * 0.85.
  Comparison<3> c(Scenario<3>{.n0 = 4, .n1 = 5, .shift = {0.25, 0.15, 0.05}, .amplitude = 0.0, .overlap = 0.0});
  EXPECT_NEAR(c.contact_result.measure0, 0.75 * 0.85, rounding);
  EXPECT_NEAR(c.plmap_result.measure0, 0.75 * 0.85, rounding);
  EXPECT_NEAR(c.plmap_result.measure1, 0.75 * 0.85, rounding);
  // Parallel planes: the projection is one translation, so both mergers' maps are exact and the
  // mortar matrices agree entry by entry however the overlap polygons are triangulated.
  EXPECT_LE(max_difference(c.plmap_result.mortar, c.contact_result.mortar), rounding);
  EXPECT_LE(largest_off_ray<3>(c.plmap_merger, c.p0, c.p1, 0.05, 0.25), rounding);
}

TEST(PlmapMerge3d, CurvedInterfaceCoversWhatContactMergeCoversAndMore) {
  // Both grids bent by 0.1 sin(pi x) sin(pi y).
  Comparison<3> c(Scenario<3>{.n0 = 4, .n1 = 5, .shift = {0.0, 0.0, 0.0}, .amplitude = 0.1, .overlap = 0.02});
  EXPECT_NEAR(c.plmap_result.measure0, c.interface0, rounding);
  EXPECT_LT(c.contact_result.measure0, c.interface0 * (1 - 1e-4));
  EXPECT_GE(c.expect_plmap_covers_contact_merge(0.25), 1);
  EXPECT_LE(largest_off_ray<3>(c.plmap_merger, c.p0, c.p1, 0.02, 0.25), 1e-9);
}

TEST(PlmapMerge3d, CurvedInterfaceWithGapCoversWhatContactMergeCoversAndMore) {
  Comparison<3> c(Scenario<3>{.n0 = 4, .n1 = 5, .shift = {0.0, 0.0, 0.05}, .amplitude = 0.1, .overlap = 0.0});
  EXPECT_GT(c.plmap_result.measure0, c.contact_result.measure0);
  EXPECT_GE(c.expect_plmap_covers_contact_merge(0.25, false), 1);
  EXPECT_LE(largest_off_ray<3>(c.plmap_merger, c.p0, c.p1, 0.1, 0.25), 1e-9);
}

// --- through GridGlue -----------------------------------------------------------------------

/// GridGlue with plmap's merger swapped in for ContactMerge: the glue's intersections carry
/// their inside and outside elements, and the corners of each, mapped through either element's
/// geometry, are the same world point on a matching flat interface (no gap).
template <int dim>
void expect_glue_matches_world_points() {
  Coupling<dim> coupling(Scenario<dim>{.n0 = 3, .n1 = 4, .shift = {}, .amplitude = 0.0, .overlap = 0.0});
  using Glue = Dune::GridGlue::GridGlue<Extractor<dim>, Extractor<dim>>;
  auto merger = std::make_shared<plmap::dune::PlmapMerge<dim>>();
  Glue glue(coupling.patch0, coupling.patch1, merger);
  glue.build();
  ASSERT_GT(glue.size(), 0u);
  double area = 0.0;
  for (const auto& is : intersections(glue)) {
    const auto inside = is.inside().geometry();
    const auto outside = is.outside().geometry();
    area += is.geometry().volume();
    for (int k = 0; k < is.geometry().corners(); ++k) {
      const auto x = inside.global(is.geometryInInside().corner(k));
      const auto y = outside.global(is.geometryInOutside().corner(k));
      EXPECT_LE((x - y).two_norm(), 1e-13) << "intersection corner " << k;
      EXPECT_LE((x - is.geometry().corner(k)).two_norm(), 1e-13);
      EXPECT_NEAR(x[dim - 1], 1.0, 1e-13);
    }
  }
  EXPECT_NEAR(area, 1.0, rounding);
  EXPECT_EQ(merger->projection().report.edges_not_inserted.size(), 0u);
}

TEST(PlmapMerge2d, GridGlueWithPlmapMergerMatchesWorldPoints) { expect_glue_matches_world_points<2>(); }
TEST(PlmapMerge3d, GridGlueWithPlmapMergerMatchesWorldPoints) { expect_glue_matches_world_points<3>(); }

// --- options and errors ---------------------------------------------------------------------

TEST(PlmapMerge3d, DistanceBoundLeavesFartherGridUncovered) {
  Coupling<3> coupling(Scenario<3>{.n0 = 3, .n1 = 4, .shift = {0.0, 0.0, 0.05}, .amplitude = 0.0, .overlap = 0.0});
  const Patch<3> p0(*coupling.patch0), p1(*coupling.patch1);
  plmap::dune::PlmapMergeOptions<3> options;
  options.projection.max_distance = 0.04;  // the gap is 0.05
  plmap::dune::PlmapMerge<3> merger(options);
  build<3>(merger, p0, p1);
  EXPECT_EQ(merger.nSimplices(), 0u);
  options.projection.max_distance = 0.06;
  options.projection.threads = 2;
  merger.set_options(options);
  build<3>(merger, p0, p1);
  EXPECT_NEAR(coupled<3>(merger, p0, p1).measure0, 1.0, rounding);
}

TEST(PlmapMerge2d, AnalyticDirectionFieldIsUsed) {
  // A slanted direction field (1, 1): grid 0's top side [0,1] x {1} is projected onto grid 1's
  // bottom side [0,1] x {1.1} shifted by 0.1 to the right, so [0, 0.9] of it is covered.
  Coupling<2> coupling(Scenario<2>{.n0 = 4, .n1 = 5, .shift = {0.0, 0.1}, .amplitude = 0.0, .overlap = 0.0});
  const Patch<2> p0(*coupling.patch0), p1(*coupling.patch1);
  plmap::dune::PlmapMergeOptions<2> options;
  options.directions = [](const Dune::FieldVector<double, 2>&) { return Dune::FieldVector<double, 2>{1.0, 1.0}; };
  plmap::dune::PlmapMerge<2> merger(options);
  build<2>(merger, p0, p1);
  EXPECT_NEAR(coupled<2>(merger, p0, p1).measure0, 0.9, rounding);
  EXPECT_NEAR(merger.projection().measures.covered_domain, 0.9, rounding);
}

TEST(PlmapMerge2d, NonSimplexElementIsRejectedByName) {
  plmap::dune::PlmapMerge<3> merger;
  const std::vector<Dune::FieldVector<double, 3>> coords = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<unsigned> quad = {0, 1, 2, 3};
  const std::vector<Dune::GeometryType> types = {Dune::GeometryTypes::quadrilateral};
  try {
    merger.build(coords, quad, types, coords, quad, types);
    FAIL() << "a quadrilateral was accepted";
  } catch (const plmap::Error& e) {
    EXPECT_NE(std::string(e.what()).find("grid 0 element 0 is not a triangle"), std::string::npos) << e.what();
  }
  EXPECT_EQ(merger.nSimplices(), 0u);
  EXPECT_THROW(merger.projection(), plmap::Error);
}

}  // namespace

namespace {

TEST(PlmapMerge3d, EmptyPatchGivesNoIntersections) {
  // A predicate that selects no face (e.g. on a process that holds none of the interface) gives
  // an empty patch: no intersections, not an error.
  Coupling<3> coupling(Scenario<3>{.n0 = 2, .n1 = 2, .shift = {}, .amplitude = 0.0, .overlap = 0.0});
  const Patch<3> p1(*coupling.patch1);
  plmap::dune::PlmapMerge<3> merger;
  build<3>(merger, Patch<3>{}, p1);
  EXPECT_EQ(merger.nSimplices(), 0u);
  build<3>(merger, p1, Patch<3>{});
  EXPECT_EQ(merger.nSimplices(), 0u);
}

}  // namespace
