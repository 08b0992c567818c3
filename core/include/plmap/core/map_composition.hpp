#pragma once
/// \file
/// Composition of maps: Xi_n ∘ ... ∘ Xi_2 ∘ Xi_1 for Xi_k: S_k -> S_(k+1), evaluated point by
/// point (the basis of morphing, paper section 5.1), forwards and backwards.
///
/// Nothing is overlaid: a composed evaluation is one evaluation per map, the image on S_(k+1) of
/// one map being the query point of the next. That image may lie on an edge or vertex of its S2
/// element (or outside it by a rounding): it is clamped into the element, and when the next map's
/// regions on that element do not contain it, the elements sharing the edge or vertex are tried
/// (the point may lie on the boundary of D there). The inverse chains InverseIndex queries, which
/// do the same by themselves.

#include <plmap/core/evaluation.hpp>
#include <plmap/core/evaluation_at_boundaries.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <memory>
#include <vector>

namespace plmap {

/// True if a and b are the same surface: the same object, or equal vertex positions and elements
/// (bit for bit, in the same order), so that element indices mean the same on both.
template <int d>
bool same_surface(const Surface<d>& a, const Surface<d>& b);

/// A chain of maps whose surfaces fit: maps[k]'s target is maps[k+1]'s domain.
template <int d>
  requires SurfaceDimension<d>
class MapComposition {
 public:
  /// `maps[0]` is applied first. Throws plmap::Error if the list is empty or a target is not the
  /// next domain (same_surface), naming the pair.
  explicit MapComposition(std::vector<std::shared_ptr<const PlMap<d>>> maps);

  std::size_t size() const { return maps_.size(); }
  const PlMap<d>& map(std::size_t k) const { return *maps_[k]; }
  const Surface<d>& domain() const { return maps_.front()->domain(); }
  const Surface<d>& target() const { return maps_.back()->target(); }

 private:
  std::vector<std::shared_ptr<const PlMap<d>>> maps_;
};

/// The composed map at one point.
template <int d>
struct ComposedEvaluation {
  bool defined = false;  ///< false: some map of the chain is undefined on the way
  /// The map (0-based) outside whose domain (forwards) or image (backwards) the point fell, or -1.
  int stopped_at = -1;
  SurfacePoint<d> point;                        ///< the result: a point of the last (first) surface
  WorldPoint<d> world = WorldPoint<d>::Zero();  ///< the result in world coordinates
};

/// Evaluates a composition with one point locator per map (copies of a prototype, prepared).
/// Like a locator, an evaluator has mutable state: give every thread its own copy.
template <int d, class Locator>
  requires PointLocator<Locator, d>
class CompositionEvaluator {
 public:
  CompositionEvaluator(const MapComposition<d>& composition, const Locator& prototype) : composition_(&composition) {
    locators_.reserve(composition.size());
    for (std::size_t k = 0; k < composition.size(); ++k) {
      locators_.push_back(prototype);
      prepare_point_locator<d>(locators_.back(), composition.map(k));
    }
  }

  /// (Xi_n ∘ ... ∘ Xi_1)(p) for p on S_1.
  ComposedEvaluation<d> operator()(const SurfacePoint<d>& p) {
    ComposedEvaluation<d> out;
    SurfacePoint<d> x = p;
    for (std::size_t k = 0; k < composition_->size(); ++k) {
      const Evaluation<d> e = k == 0 ? evaluate(composition_->map(0), x, locators_[0])
                                     : evaluate_on_any_incident_element(composition_->map(k), x, locators_[k]);
      if (!e.in_domain) {
        out.stopped_at = static_cast<int>(k);
        return out;
      }
      x = e.image;
      out.world = e.world;
    }
    out.defined = true;
    out.point = x;
    return out;
  }

 private:
  const MapComposition<d>* composition_;
  std::vector<Locator> locators_;
};

/// The inverse of a composition, (Xi_n ∘ ... ∘ Xi_1)^{-1} = Xi_1^{-1} ∘ ... ∘ Xi_n^{-1}, through one
/// InverseIndex per map (built in the constructor). Queries are const and thread-safe.
template <int d>
  requires SurfaceDimension<d>
class InverseComposition {
 public:
  explicit InverseComposition(const MapComposition<d>& composition, InverseOptions options = {}) {
    indices_.reserve(composition.size());
    for (std::size_t k = 0; k < composition.size(); ++k) indices_.emplace_back(composition.map(k), options);
  }

  /// The preimage on S_1 of y on S_(n+1).
  ComposedEvaluation<d> operator()(const SurfacePoint<d>& y) const {
    ComposedEvaluation<d> out;
    SurfacePoint<d> x = y;
    for (std::size_t k = indices_.size(); k-- > 0;) {
      const InverseEvaluation<d> e = inverse_evaluate(indices_[k], x);
      if (!e.in_image) {
        out.stopped_at = static_cast<int>(k);
        return out;
      }
      x = e.preimage;
      out.world = e.world;
    }
    out.defined = true;
    out.point = x;
    return out;
  }

 private:
  std::vector<InverseIndex<d>> indices_;
};

/// The composition at many points on `threads` threads (0: all), parallel_ranges as
/// evaluate_batch. Throws plmap::Error first if sizes differ or a point names no S_1 element.
template <int d, class Locator>
  requires PointLocator<Locator, d>
void evaluate_composition_batch(const MapComposition<d>& composition, std::span<const SurfacePoint<d>> points,
                                std::span<ComposedEvaluation<d>> out, const Locator& locator, unsigned threads = 0) {
  if (out.size() != points.size())
    throw Error("evaluate_composition_batch: output span size differs from the number of points");
  for (const auto& p : points)
    if (p.element < 0 || p.element >= composition.domain().element_count())
      throw Error("evaluate_composition_batch: query point on element " + std::to_string(p.element) +
                  ", but the first surface has " + std::to_string(composition.domain().element_count()) + " elements");
  const CompositionEvaluator<d, Locator> prepared(composition, locator);
  parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end) {
    CompositionEvaluator<d, Locator> evaluator = prepared;
    for (std::size_t i = begin; i < end; ++i) out[i] = evaluator(points[i]);
  });
}

extern template class MapComposition<1>;
extern template class MapComposition<2>;
extern template bool same_surface(const Surface<1>&, const Surface<1>&);
extern template bool same_surface(const Surface<2>&, const Surface<2>&);

}  // namespace plmap
