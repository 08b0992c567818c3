#pragma once
/// \file
/// Strategy family "smoothing weights" (DESIGN.md §2, paper 3.3.2): the weights of a
/// convex-combination parametrization. Smoothing places every free node at Σ_j w_j · neighbour_j;
/// a model computes the w_j of one node from the geometry of its star on S2: the node's image
/// `center` and its neighbours' images `ring`, in the cyclic (counter-clockwise) order of the
/// neighbours around the node on S1.
///
/// A model returns one weight per ring vertex, every weight > 0 and their sum 1 (Tutte's and
/// Floater's embedding theorems need exactly this), or nothing when the star is degenerate
/// (a zero-length spoke, a zero angle); the caller then falls back to uniform weights.
///
/// Models: FloaterWeights (shape-preserving, paper default), MeanValueWeights, UniformWeights.

#include <Eigen/Core>

#include <concepts>
#include <optional>
#include <span>
#include <vector>

namespace plmap {

template <class W>
concept SmoothingWeights = requires(const W& w, const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) {
  { w.weights(center, ring) } -> std::same_as<std::optional<std::vector<double>>>;
};

/// Divides by the sum; nothing if a weight is not finite and positive (the model's formula met a
/// degenerate star), so that no caller ever solves with a weight that breaks the theorem.
std::optional<std::vector<double>> normalized_positive_weights(std::vector<double> weights);

}  // namespace plmap
