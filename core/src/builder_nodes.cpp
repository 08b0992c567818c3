// The builder's nodes as finalize reads them (builder_nodes.hpp).

#include "builder_nodes.hpp"

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

namespace plmap::detail {

void throw_not_in_element(Index t, Index vertex) {
  throw BuilderError(fmt::format("internal: an image is re-expressed on S2 element {}, which does not "
                                 "contain its S2 vertex {}",
                                 t, vertex));
}

}  // namespace plmap::detail
