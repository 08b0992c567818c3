#include <plmap/core/errors.hpp>
#include <plmap/core/map_composition.hpp>

#include <string>

namespace plmap {

template <int d>
bool same_surface(const Surface<d>& a, const Surface<d>& b) {
  return &a == &b || (a.vertices() == b.vertices() && a.elements() == b.elements());
}

template <int d>
  requires SurfaceDimension<d>
MapComposition<d>::MapComposition(std::vector<std::shared_ptr<const PlMap<d>>> maps) : maps_(std::move(maps)) {
  if (maps_.empty()) throw Error("map composition: no maps given");
  for (std::size_t k = 0; k < maps_.size(); ++k)
    if (!maps_[k]) throw Error("map composition: map " + std::to_string(k + 1) + " is null");
  for (std::size_t k = 0; k + 1 < maps_.size(); ++k)
    if (!same_surface(maps_[k]->target(), maps_[k + 1]->domain()))
      throw Error("map composition: the target surface of map " + std::to_string(k + 1) + " (" +
                  std::to_string(maps_[k]->target().element_count()) + " elements) is not the domain surface of map " +
                  std::to_string(k + 2) + " (" + std::to_string(maps_[k + 1]->domain().element_count()) + " elements)");
}

template bool same_surface(const Surface<1>&, const Surface<1>&);
template bool same_surface(const Surface<2>&, const Surface<2>&);
template class MapComposition<1>;
template class MapComposition<2>;

}  // namespace plmap
