// The map factory (paper section 3.1): collects nodes and edge preimages on S1, then finalize()
// turns them into the compact PlMap. The public entry points here forward to the builder's state
// (map_builder_impl.hpp), which checks every entry and places it on S1; finalize() hands what it
// collected to the finalize phases (finalize_phases.hpp).

#include "builder_nodes.hpp"
#include "finalize_assembly.hpp"
#include "finalize_phases.hpp"
#include "finalize_reuse.hpp"
#include "map_arrays.hpp"
#include "map_builder_impl.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/freed_heap.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/snapping.hpp>

#include <fmt/format.h>

#include <exception>
#include <span>

namespace plmap {

namespace {

using detail::Place;
using detail::PlaceKind;

}  // namespace

// ==== public interface ============================================================================

template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::MapBuilder(std::shared_ptr<const Surface<d>> domain,
                          std::shared_ptr<const Surface<d>> target, BuilderOptions options)
    : impl_(std::make_unique<Impl>(std::move(domain), std::move(target), options)) {}

template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::~MapBuilder() = default;
template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::MapBuilder(MapBuilder&&) noexcept = default;
template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>& MapBuilder<d>::operator=(MapBuilder&&) noexcept = default;

template <int d>
  requires SurfaceDimension<d>
const Surface<d>& MapBuilder<d>::domain() const {
  return *impl_->s1;
}
template <int d>
  requires SurfaceDimension<d>
const Surface<d>& MapBuilder<d>::target() const {
  return *impl_->s2;
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage(Index target_vertex,
                                                                    const SurfacePoint<d>& at) {
  return impl_->add_vertex_preimage(target_vertex, impl_->place_of(at, "vertex preimage"));
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage_at_vertex(Index target_vertex,
                                                                              Index domain_vertex) {
  impl_->check_s1_vertex_with_elements(domain_vertex);
  Place<d> p;
  p.kind = PlaceKind::vertex;
  p.index = domain_vertex;
  return impl_->add_vertex_preimage(target_vertex, p);
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage_on_edge(Index target_vertex,
                                                                            Index domain_edge, double t)
  requires(d == 2)
{
  // Clang 14 compiles members whose constraints fail when `template class MapBuilder<1>;`
  // instantiates the class (fixed in clang 15); the `if constexpr` keeps such bodies
  // compiling there (scripts/fuzz builds with Debian's clang). Same below.
  if constexpr (d == 2) {
    if (domain_edge < 0 || domain_edge >= impl_->s1->edge_count())
      throw BuilderError(fmt::format("S1 edge {} does not exist", domain_edge));
    if (!(t >= -impl_->tol() && t <= 1.0 + impl_->tol()))
      throw BuilderError(fmt::format("parameter {} on S1 edge {} is outside [0, 1]", t, domain_edge));
    Place<d> p;
    const auto ev = impl_->s1->edge_vertices(domain_edge);
    if (const EdgeSnap snap = snap_edge_parameter(t, impl_->tol()); snap != EdgeSnap::inside) {
      p.kind = PlaceKind::vertex;
      p.index = ev[snap == EdgeSnap::first_vertex ? 0 : 1];
    } else {
      p.kind = PlaceKind::edge;
      p.index = domain_edge;
      p.coords(0) = t;
    }
    return impl_->add_vertex_preimage(target_vertex, p);
  }
  __builtin_unreachable();  // d == 1 never calls it (the constraint)
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_ghost_node(Index domain_vertex,
                                                               const SurfacePoint<d>& image) {
  return impl_->add_ghost_node(domain_vertex, impl_->support_of(image, "ghost node image"));
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_edge)
  requires(d == 2)
{
  if constexpr (d == 2) {
    add_edge(target_edge, std::span<const EdgeCrossing>{});
  }
}

namespace {

/// The crossings as places on S1, written into the builder's reused buffer.
template <int d, class Impl>
const std::vector<typename Impl::CrossingPlace>& crossing_places(Impl& im, Index target_edge,
                                                                 std::span<const EdgeCrossing> crossings) {
  auto& places = im.places_scratch;
  places.clear();
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    const auto& c = crossings[i];
    if (c.domain_edge < 0 || c.domain_edge >= im.s1->edge_count())
      throw BuilderError(fmt::format("crossing {} of S2 edge {}: S1 edge {} does not exist", i,
                                     target_edge, c.domain_edge));
    if (!(c.domain_parameter >= -im.tol() && c.domain_parameter <= 1.0 + im.tol()))
      throw BuilderError(fmt::format("crossing {} of S2 edge {}: parameter {} is outside [0, 1]", i,
                                     target_edge, c.domain_parameter));
    Place<d> p;
    const auto ev = im.s1->edge_vertices(c.domain_edge);
    if (const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, im.tol()); snap != EdgeSnap::inside) {
      p.kind = PlaceKind::vertex;
      p.index = ev[snap == EdgeSnap::first_vertex ? 0 : 1];
    } else {
      p.kind = PlaceKind::edge;
      p.index = c.domain_edge;
      p.coords(0) = c.domain_parameter;
    }
    places.push_back({p, c.target_parameter});
  }
  return places;
}

template <int d, class Impl>
const std::vector<typename Impl::CrossingPlace>& crossing_places(Impl& im,
                                                                 std::span<const VertexCrossing> crossings) {
  auto& places = im.places_scratch;
  places.clear();
  for (const auto& c : crossings) {
    im.check_s1_vertex(c.domain_vertex);
    Place<d> p;
    p.kind = PlaceKind::vertex;
    p.index = c.domain_vertex;
    places.push_back({p, c.target_parameter});
  }
  return places;
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_edge, std::span<const EdgeCrossing> crossings)
  requires(d == 2)
{
  if constexpr (d == 2) {
    add_edge_piece(target_edge, crossings, PieceStart::first_vertex, PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_piece(Index target_edge, std::span<const EdgeCrossing> crossings, PieceStart start,
                                   PieceEnd end, PieceRimNodes rims)
  requires(d == 2)
{
  if constexpr (d == 2) {
    auto& im = *impl_;
    im.check_s2_edge(target_edge);
    const auto ev = im.s2->edge_vertices(target_edge);
    if ((start == PieceStart::rim_node && rims.start == invalid_index) ||
        (end == PieceEnd::rim_node && rims.end == invalid_index))
      throw BuilderError(fmt::format("a piece of S2 edge {} starts or ends at a rim node but names none", target_edge));
    im.insert_edge_preimage(target_edge, ev[0], ev[1], crossing_places<d>(im, target_edge, crossings),
                            start == PieceStart::first_vertex, end == PieceEnd::second_vertex,
                            start == PieceStart::rim_node ? rims.start : invalid_index,
                            end == PieceEnd::rim_node ? rims.end : invalid_index);
  }
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_rim_node(const SurfacePoint<d>& at, const SurfacePoint<d>& image)
  requires(d == 2)
{
  if constexpr (d == 2) {
    return impl_->add_rim_node(impl_->place_of(at, "rim node"), impl_->support_of(image, "rim node image"));
  }
  __builtin_unreachable();
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_rim_edge(NodeHandle a, NodeHandle b)
  requires(d == 2)
{
  if constexpr (d == 2) {
    impl_->add_rim_edge(a, b);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_element, std::span<const VertexCrossing> crossings)
  requires(d == 1)
{
  if constexpr (d == 1) {
    add_edge_piece(target_element, crossings, PieceStart::first_vertex, PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_piece(Index target_element, std::span<const VertexCrossing> crossings,
                                   PieceStart start, PieceEnd end)
  requires(d == 1)
{
  if constexpr (d == 1) {
    auto& im = *impl_;
    im.check_s2_element(target_element);
    const auto& c = im.s2->element(target_element);
    im.insert_edge_preimage(target_element, c[0], c[1], crossing_places<d>(im, crossings),
                            start == PieceStart::first_vertex, end == PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_target_element(Index target_element) {
  impl_->check_s2_element(target_element);
  if constexpr (d == 2) {
    for (int k = 0; k < 3; ++k) {
      const Index e = impl_->s2->element_edge(target_element, k);
      if (!impl_->edge_inserted[e]) add_edge(e);
    }
  } else {
    if (!impl_->edge_inserted[target_element]) add_edge(target_element);
  }
}

template <int d>
  requires SurfaceDimension<d>
std::optional<typename MapBuilder<d>::NodeHandle> MapBuilder<d>::vertex_preimage(Index target_vertex) const {
  impl_->check_s2_vertex(target_vertex);
  const Index n = impl_->preimage_of_target_vertex[target_vertex];
  if (n == invalid_index) return std::nullopt;
  return n;
}

template <int d>
  requires SurfaceDimension<d>
bool MapBuilder<d>::has_edge(Index target_edge) const {
  if (target_edge < 0 || target_edge >= static_cast<Index>(impl_->edge_inserted.size()))
    throw BuilderError(fmt::format("S2 edge {} does not exist", target_edge));
  const char state = impl_->edge_inserted[target_edge];
  return state == Impl::edge_complete || state == Impl::edge_partial;
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_outside_domain(Index target_edge) {
  if (target_edge < 0 || target_edge >= static_cast<Index>(impl_->edge_inserted.size()))
    throw BuilderError(fmt::format("S2 edge {} does not exist", target_edge));
  if (impl_->edge_inserted[target_edge] == Impl::edge_complete ||
      impl_->edge_inserted[target_edge] == Impl::edge_partial)
    throw BuilderError(fmt::format("S2 edge {} has a preimage; it cannot lie outside the domain", target_edge));
  impl_->edge_inserted[target_edge] = Impl::edge_outside_domain;
}

// ==== finalize ====================================================================================
// The phases live in their own units (finalize_phases.hpp); here the builder hands them what it
// collected.

template <int d>
  requires SurfaceDimension<d>
PlMap<d> MapBuilder<d>::finalize(FinalizeReport* report) && {
  auto impl = std::move(impl_);
  auto& im = *impl;
  detail::BuilderContents<d> contents{*im.s1, *im.s2, im.options, im.nodes, im.node_at_domain_vertex,
                                      im.segments, im.edge_inserted};
  if constexpr (d == 1) {
    MapData<1> m = detail::finalize_polylines(contents, report);
    detail::shrink_to_fit(m);
    return PlMap<1>(im.s1, im.s2, std::move(m));
  } else {
    // The stored form: the graph arrays only of the elements whose regions do not tile them.
    detail::AssembledMap assembled = detail::finalize_triangles(contents, report);
    StoredGraph graph = detail::hand_over_stored_form(assembled);
    detail::shrink_to_fit(assembled.map);
    PlMap<2> map(im.s1, im.s2, std::move(assembled.map), std::move(graph));
    // Finalize freed the builder's arrays, the map's parts and its graph arrays, most of it into
    // malloc's heap, where it stays resident: what the caller does next with the map (the
    // projection's fold test and sheet selection) would otherwise stand on top of it (on the femur
    // pair 1.8 MiB, as much as the sheet selection adds).
    impl.reset();
    give_freed_heap_back();
    return map;
  }
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d> MapBuilder<d>::finalize_reusing(const PlMap<d>& previous, std::span<const char> reuse, FinalizeReport* report) &&
  requires(d == 2)
{
  // The explicit instantiation of MapBuilder<1> below makes clang 14 compile this body for d = 1
  // despite the constraint; `if constexpr` keeps the d = 2 code out of it.
  if constexpr (d != 2) {
    throw BuilderError("finalize_reusing is for triangle surfaces");
  } else {
    if (impl_->options.orientation == 0)
      throw BuilderError("finalize_reusing needs the map's orientation given (BuilderOptions::orientation)");
    if (impl_->options.drop_conflicting_edges)
      throw BuilderError("finalize_reusing does not drop conflicting edges");
    if (&previous.domain() != impl_->s1.get() || &previous.target() != impl_->s2.get())
      throw BuilderError("finalize_reusing needs the previous map on the builder's surfaces");
    const detail::ElementReuse reused(previous, reuse);
    auto impl = std::move(impl_);
    auto& im = *impl;
    detail::BuilderContents<d> contents{*im.s1, *im.s2, im.options, im.nodes, im.node_at_domain_vertex,
                                        im.segments, im.edge_inserted};
    detail::AssembledMap assembled = detail::finalize_triangles(contents, report, &reused);
    StoredGraph graph = detail::hand_over_stored_form(assembled);
    detail::shrink_to_fit(assembled.map);
    return PlMap<2>(im.s1, im.s2, std::move(assembled.map), std::move(graph));
  }
}

template class MapBuilder<1>;
template class MapBuilder<2>;

}  // namespace plmap
