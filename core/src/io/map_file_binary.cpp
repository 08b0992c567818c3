#include "plmap/core/io/map_file_binary.hpp"

#include "binary_container.hpp"
#include "map_file_binary_table.hpp"
#include "region_map_derivation.hpp"
#include "plmap/core/errors.hpp"
#include "plmap/core/map_validation.hpp"
#include "plmap/core/parallel_ranges.hpp"
#include "plmap/core/surface_fingerprint.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>
#include <thread>
#include <type_traits>

namespace plmap {
namespace {

using binary::Container;
using binary::InArray;
using binary::OutArray;

// The arrays are written and read as the bytes of these types; the static_asserts make sure
// that they have no padding, so that a vector of them is the file's row-major array.
template <int d>
constexpr bool layouts_are_packed =
    sizeof(WorldPoint<d>) == (d + 1) * sizeof(double) &&
    sizeof(ElementCorners<d>) == (d + 1) * sizeof(Index) &&
    sizeof(LocalPoint<d>) == d * sizeof(double) &&
    sizeof(AffineMap<d>) == d * (d + 1) * sizeof(double) &&
    sizeof(std::array<Index, d + 1>) == (d + 1) * sizeof(Index);
static_assert(layouts_are_packed<1> && layouts_are_packed<2>);
static_assert(sizeof(NodeType) == 1 && sizeof(GraphEdgeKind) == 1);

/// The scalars of a vector of fixed-size arrays (Eigen vectors, std::array), as one flat array.
/// Through the vector's data(), never through its first element: an empty vector has none.
template <class Scalar, class T>
Scalar* scalars(std::vector<T>& v) {
  return reinterpret_cast<Scalar*>(v.data());
}
template <class Scalar, class T>
const Scalar* scalars(const std::vector<T>& v) {
  return reinterpret_cast<const Scalar*>(v.data());
}

// ================================================================================================
// Groups of local indices
// ================================================================================================
//
// Most index arrays of a map hold, per S1 element, indices of that element's nodes or regions,
// of which an element has a few dozen. The file stores them relative to the element's first
// node (region), in one or two bytes, with the largest value of the type meaning "none" (-1):
// this is what makes the binary file a quarter of the text file. A visitor calls
// f(base, limit, first, last): entries [first, last) are indices in [base, base + limit) or -1.

template <int d>
struct LocalGroups {
  const MapData<d>& m;
  std::size_t elements;

  template <class F>
  void neighbors(F&& f) const {
    for (std::size_t t = 0; t < elements; ++t) {
      const Index base = m.node_begin[t], limit = m.node_begin[t + 1] - base;
      for (Index n = base; n < m.node_begin[t + 1]; ++n) {
        f(base, limit, std::size_t(m.neighbor_begin[n]), std::size_t(m.neighbor_begin[n + 1]));
      }
    }
  }
  template <class F>
  void edge_nodes(F&& f) const {
    for (std::size_t t = 0; t < elements; ++t) {
      const Index base = m.node_begin[t], limit = m.node_begin[t + 1] - base;
      f(base, limit, std::size_t(m.edge_node_begin[3 * t]), std::size_t(m.edge_node_begin[3 * t + 3]));
    }
  }
  template <class F>
  void region_corners(F&& f) const {
    for (std::size_t t = 0; t < elements; ++t) {
      f(m.node_begin[t], m.node_begin[t + 1] - m.node_begin[t], (d + 1) * std::size_t(m.region_begin[t]),
        (d + 1) * std::size_t(m.region_begin[t + 1]));
    }
  }
  template <class F>
  void region_neighbors(F&& f) const {
    for (std::size_t t = 0; t < elements; ++t) {
      f(m.region_begin[t], m.region_begin[t + 1] - m.region_begin[t], (d + 1) * std::size_t(m.region_begin[t]),
        (d + 1) * std::size_t(m.region_begin[t + 1]));
    }
  }
  template <class F>
  void start_region(F&& f) const {
    for (std::size_t t = 0; t < elements; ++t) {
      f(m.region_begin[t], m.region_begin[t + 1] - m.region_begin[t], t, t + 1);
    }
  }
  /// The edge arrays are grouped by element only if they have the d = 2 layout (3 entries per
  /// element); PlMap checks that for d = 2 only.
  bool edge_layout_ok() const {
    return m.edge_node_begin.size() == 3 * elements + 1 &&
           m.edge_node.size() == static_cast<std::size_t>(m.edge_node_begin.back());
  }
};

// ================================================================================================
// Writing
// ================================================================================================

template <class T>
OutArray raw_array(std::string name, std::string dtype, std::vector<std::uint64_t> shape,
                   const std::vector<T>& values) {
  OutArray a;
  a.name = std::move(name);
  a.dtype = std::move(dtype);
  a.shape = std::move(shape);
  a.encoding = "raw";
  a.data = values.data();
  a.bytes = values.size() * sizeof(T);
  return a;
}

template <class Stored>
void fill_owned(OutArray& a, std::size_t count, auto&& value_of) {
  a.owned.resize(count * sizeof(Stored));
  auto* out = a.owned.data();
  for (std::size_t i = 0; i < count; ++i) {
    const Stored v = static_cast<Stored>(value_of(i));
    std::memcpy(out + i * sizeof(Stored), &v, sizeof(Stored));
  }
  a.data = a.owned.data();
  a.bytes = a.owned.size();
}

/// A begin array (0, then non-decreasing) as the sizes of its ranges, in 1, 2 or 4 bytes.
OutArray counts_array(std::string name, const std::vector<Index>& begin) {
  if (begin.empty() || begin.front() != 0 || !std::is_sorted(begin.begin(), begin.end())) {
    return raw_array(std::move(name), "<i4", {begin.size()}, begin);
  }
  Index largest = 0;
  for (std::size_t i = 0; i + 1 < begin.size(); ++i) largest = std::max(largest, begin[i + 1] - begin[i]);
  OutArray a;
  a.name = std::move(name);
  a.shape = {begin.size() - 1};
  a.encoding = "counts";
  auto count = [&](std::size_t i) { return begin[i + 1] - begin[i]; };
  if (largest <= 0xff) {
    a.dtype = "|u1";
    fill_owned<std::uint8_t>(a, begin.size() - 1, count);
  } else if (largest <= 0xffff) {
    a.dtype = "<u2";
    fill_owned<std::uint16_t>(a, begin.size() - 1, count);
  } else {
    a.dtype = "<u4";
    fill_owned<std::uint32_t>(a, begin.size() - 1, count);
  }
  return a;
}

/// Indices grouped by a visitor (LocalGroups) as offsets from their group's base, in 1 or 2
/// bytes; falls back to raw 32-bit indices if a value lies outside its group (a map the loader
/// would refuse, but one the writer can still store exactly) or a group is too large.
template <class Visit>
OutArray local_array(std::string name, std::string base, std::vector<std::uint64_t> shape,
                     const Index* values, std::size_t count, Visit&& visit) {
  bool inside = true;
  Index largest_limit = 0;
  visit([&](Index group_base, Index limit, std::size_t first, std::size_t last) {
    largest_limit = std::max(largest_limit, limit);
    for (std::size_t i = first; i < last; ++i) {
      const Index v = values[i];
      inside &= v == invalid_index || (v >= group_base && v - group_base < limit);
    }
  });
  OutArray a;
  a.name = std::move(name);
  a.shape = std::move(shape);
  if (!inside || largest_limit >= 0xffff) {
    a.dtype = "<i4";
    a.encoding = "raw";
    a.data = values;
    a.bytes = count * sizeof(Index);
    return a;
  }
  a.encoding = "local";
  a.base = std::move(base);
  auto encode = [&]<class Stored>(Stored none) {
    a.owned.resize(count * sizeof(Stored));
    auto* out = a.owned.data();
    visit([&](Index group_base, Index, std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i) {
        const Stored v = values[i] == invalid_index ? none : static_cast<Stored>(values[i] - group_base);
        std::memcpy(out + i * sizeof(Stored), &v, sizeof(Stored));
      }
    });
    a.data = a.owned.data();
    a.bytes = a.owned.size();
  };
  if (largest_limit < 0xff) {
    a.dtype = "|u1";
    encode(std::uint8_t{0xff});
  } else {
    a.dtype = "<u2";
    encode(std::uint16_t{0xffff});
  }
  return a;
}

void require_finite(const double* values, std::size_t count, std::string_view array) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidMapError(fmt::format(
          "cannot save map: {} holds a non-finite number ({}); map files store finite numbers only",
          array, values[i]));
    }
  }
}

/// The region maps: where recomputing them from the nodes gives the stored bits (every region
/// of a freshly built map), only the regions where it does not are stored, with the CRC-32 of
/// the whole array so that the reader can confirm its recomputation; if most regions differ,
/// the array is stored whole.
template <int d>
void add_region_maps(const PlMap<d>& map, std::vector<OutArray>& a, nlohmann::json& toc, unsigned threads) {
  const MapData<d>& m = map.stored();
  const std::size_t R = m.region_map.size();
  std::vector<unsigned char> exact(R);
  parallel_ranges(R, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const std::optional<AffineMap<d>> derived = binary::derived_region_map(m, map.target(), r);
      exact[r] = derived && std::memcmp(derived->data(), m.region_map[r].data(), sizeof(AffineMap<d>)) == 0;
    }
  });
  std::vector<Index> exceptions;
  for (std::size_t r = 0; r < R; ++r) {
    if (!exact[r]) exceptions.push_back(static_cast<Index>(r));
  }
  constexpr std::uint64_t D = d;
  if (2 * exceptions.size() > R) {
    a.push_back(raw_array("region_map", "<f8", {R, D + 1, D}, m.region_map));
    return;
  }
  toc["region_map"] = {{"derived", true},
                       {"crc32", binary::crc32_parallel(m.region_map.data(), R * sizeof(AffineMap<d>), threads)}};
  OutArray values;
  values.name = "region_map_exception";
  values.dtype = "<f8";
  values.shape = {exceptions.size(), D + 1, D};
  values.encoding = "raw";
  values.owned.resize(exceptions.size() * sizeof(AffineMap<d>));
  for (std::size_t i = 0; i < exceptions.size(); ++i) {
    std::memcpy(values.owned.data() + i * sizeof(AffineMap<d>), m.region_map[exceptions[i]].data(), sizeof(AffineMap<d>));
  }
  values.data = values.owned.data();
  values.bytes = values.owned.size();
  OutArray regions;
  regions.name = "region_map_exception_region";
  regions.dtype = "<i4";
  regions.shape = {exceptions.size()};
  regions.encoding = "raw";
  fill_owned<Index>(regions, exceptions.size(), [&](std::size_t i) { return exceptions[i]; });
  a.push_back(std::move(regions));
  a.push_back(std::move(values));
}

/// A begin array (0, then the running sums) of counts.
std::vector<Index> begin_of_counts(const std::vector<Index>& count) {
  std::vector<Index> begin(count.size() + 1, 0);
  for (std::size_t i = 0; i < count.size(); ++i) begin[i + 1] = begin[i] + count[i];
  return begin;
}

/// A triangle map's stored graph (PlMap::stored_graph): the graph arrays of the few elements
/// whose regions do not tile them, with global indices (raw: they are a small part of the file).
void add_stored_graph(const StoredGraph& g, std::vector<OutArray>& a) {
  const std::uint64_t G = g.element.size();
  a.push_back(raw_array("graph_element", "<i4", {G}, g.element));
  OutArray neighbor_begin = counts_array("graph_neighbor_begin", begin_of_counts(g.neighbor_count));
  OutArray edge_node_begin = counts_array("graph_edge_node_begin", begin_of_counts(g.edge_node_count));
  // counts_array may fall back to raw begin arrays, which point into its argument: keep owned bytes
  for (OutArray* x : {&neighbor_begin, &edge_node_begin}) {
    if (x->owned.empty() && x->bytes != 0) {
      x->owned.assign(static_cast<const unsigned char*>(x->data), static_cast<const unsigned char*>(x->data) + x->bytes);
      x->data = x->owned.data();
    }
  }
  a.push_back(std::move(neighbor_begin));
  a.push_back(raw_array("graph_neighbor", "<i4", {g.neighbor.size()}, g.neighbor));
  a.push_back(raw_array("graph_neighbor_edge_kind", "|u1", {g.neighbor_edge_kind.size()}, g.neighbor_edge_kind));
  a.push_back(std::move(edge_node_begin));
  a.push_back(raw_array("graph_edge_node", "<i4", {g.edge_node.size()}, g.edge_node));
  a.push_back(raw_array("graph_region_neighbors", "<i4", {g.region_neighbors.size(), 3}, g.region_neighbors));
}

template <int d>
std::vector<OutArray> map_arrays(const PlMap<d>& map, nlohmann::json& toc, unsigned threads) {
  // What the map stores, never what it would derive: writing derives nothing.
  const MapData<d>& m = map.stored();
  const auto T = static_cast<std::uint64_t>(map.domain().element_count());
  const std::uint64_t N = m.node_type.size(), R = m.region_target.size();
  const std::uint64_t D = d;
  require_finite(scalars<double>(m.node_position), N * d, "node_position");
  require_finite(scalars<double>(map.domain().vertices()), map.domain().vertices().size() * (d + 1), "domain vertices");
  require_finite(scalars<double>(map.target().vertices()), map.target().vertices().size() * (d + 1), "target vertices");
  require_finite(scalars<double>(m.node_image_local), N * d, "node_image");
  require_finite(scalars<double>(m.region_map), R * d * (d + 1), "region_map");

  std::vector<OutArray> a;
  auto surface = [&](const Surface<d>& s, const char* prefix) {
    a.push_back(raw_array(fmt::format("{}_vertices", prefix), "<f8", {s.vertices().size(), D + 1}, s.vertices()));
    a.push_back(raw_array(fmt::format("{}_elements", prefix), "<i4", {s.elements().size(), D + 1}, s.elements()));
  };
  surface(map.domain(), "domain");
  surface(map.target(), "target");

  const LocalGroups<d> groups{m, T};
  a.push_back(counts_array("node_begin", m.node_begin));
  a.push_back(raw_array("node_type", "|u1", {N}, m.node_type));
  a.push_back(raw_array("node_location", "|i1", {N}, m.node_location));
  a.push_back(raw_array("node_position", "<f8", {N, D}, m.node_position));
  a.push_back(raw_array("node_image_element", "<i4", {N}, m.node_image_element));
  a.push_back(raw_array("node_image_local", "<f8", {N, D}, m.node_image_local));
  a.push_back(raw_array("node_target", "<i4", {N}, m.node_target));

  if constexpr (d == 1) {
    a.push_back(counts_array("neighbor_begin", m.neighbor_begin));
    a.push_back(local_array("neighbor", "node_begin", {m.neighbor.size()}, m.neighbor.data(), m.neighbor.size(),
                            [&](auto&& f) { groups.neighbors(f); }));
    a.push_back(raw_array("neighbor_edge_kind", "|u1", {m.neighbor_edge_kind.size()}, m.neighbor_edge_kind));
    a.push_back(counts_array("edge_node_begin", m.edge_node_begin));
    a.push_back(raw_array("edge_node", "<i4", {m.edge_node.size()}, m.edge_node));
  } else {
    add_stored_graph(map.stored_graph(), a);
  }
  a.push_back(counts_array("region_begin", m.region_begin));
  a.push_back(local_array("region_corners", "node_begin", {R, D + 1}, scalars<Index>(m.region_corners), R * (d + 1),
                          [&](auto&& f) { groups.region_corners(f); }));
  if constexpr (d == 1) {
    a.push_back(local_array("region_neighbors", "region_begin", {R, D + 1}, scalars<Index>(m.region_neighbors),
                            R * (d + 1), [&](auto&& f) { groups.region_neighbors(f); }));
  }
  a.push_back(raw_array("region_target", "<i4", {R}, m.region_target));
  // Eigen stores [A | b] column by column: the file's shape (R, d+1, d) is its columns.
  add_region_maps(map, a, toc, threads);
  a.push_back(local_array("start_region", "region_begin", {T}, m.start_region.data(), T,
                          [&](auto&& f) { groups.start_region(f); }));
  return a;
}

// ================================================================================================
// Reading
// ================================================================================================

/// Reads the arrays of one map out of a checked container. Each accessor checks dtype, shape
/// and encoding before it copies or decodes.
class MapArrayReader {
 public:
  MapArrayReader(const Container& c, const MapReadOptions& options)
      : c_(c), options_(options), caller_(std::this_thread::get_id()) {}

  const InArray& get(const std::string& name, std::initializer_list<std::uint64_t> shape_tail,
                     std::uint64_t rows) {
    const InArray& a = c_.array(name);
    if (a.shape.size() != 1 + shape_tail.size() || a.shape[0] != rows ||
        !std::equal(shape_tail.begin(), shape_tail.end(), a.shape.begin() + 1)) {
      std::string expected = fmt::format("{}", rows);
      for (std::uint64_t x : shape_tail) expected += fmt::format(", {}", x);
      c_.fail(a, fmt::format("shape is ({}), expected ({})", fmt::join(a.shape, ", "), expected));
    }
    // The checksums were verified all at once (Container::verify_all_checksums). Progress is
    // reported from the caller's thread only (progress.hpp): the arrays are read side by side.
    const std::uint64_t done = done_ += a.bytes;
    if (std::this_thread::get_id() == caller_) report_progress(options_.progress, "reading map", done, c_.file_bytes());
    return a;
  }

  /// The number of rows of an array (its first extent), as a count that fits an Index.
  std::uint64_t rows(const std::string& name) {
    const InArray& a = c_.array(name);
    if (a.shape[0] > static_cast<std::uint64_t>(std::numeric_limits<Index>::max())) {
      c_.fail(a, fmt::format("{} rows is more than a map can index", a.shape[0]));
    }
    return a.shape[0];
  }

  void expect(const InArray& a, std::string_view dtype, std::string_view encoding) {
    if (a.dtype != dtype) c_.fail(a, fmt::format("dtype {}, expected {}", a.dtype, dtype));
    if (a.encoding != encoding) c_.fail(a, fmt::format("encoding '{}', expected '{}'", a.encoding, encoding));
  }

  /// Copies a raw array into `out` (resized to the array's items / items_per_value values).
  template <class T>
  void raw(const InArray& a, std::string_view dtype, std::vector<T>& out) {
    expect(a, dtype, "raw");
    const std::size_t count = a.bytes / sizeof(T);
    if constexpr (std::is_trivially_copyable_v<T>) {
      if (reinterpret_cast<std::uintptr_t>(a.data) % alignof(T) == 0) {
        // One pass that allocates and copies: resize would zero-fill every page first. (Eigen
        // vectors are not trivially copyable, but their resize leaves the memory untouched.)
        const T* first = reinterpret_cast<const T*>(a.data);
        out.assign(first, first + count);
        return;
      }
    }
    {
      out.resize(count);
      if (a.bytes != 0) std::memcpy(static_cast<void*>(out.data()), a.data, a.bytes);
    }
  }

  /// A begin array, stored raw or as counts.
  std::vector<Index> begin_array(const InArray& a) {
    std::vector<Index> out;
    if (a.encoding == "raw") {
      raw(a, "<i4", out);
      return out;
    }
    if (a.encoding != "counts") c_.fail(a, fmt::format("unknown encoding '{}'", a.encoding));
    out.resize(a.items + 1);
    std::uint64_t sum = 0;
    auto decode = [&]<class Stored>(Stored) {
      for (std::size_t i = 0; i < a.items; ++i) {
        Stored v;
        std::memcpy(&v, a.data + i * sizeof(Stored), sizeof v);
        sum += v;
        if (sum > static_cast<std::uint64_t>(std::numeric_limits<Index>::max())) {
          c_.fail(a, "the counts add up to more than a map can index");
        }
        out[i + 1] = static_cast<Index>(sum);
      }
    };
    if (a.dtype == "|u1") {
      decode(std::uint8_t{});
    } else if (a.dtype == "<u2") {
      decode(std::uint16_t{});
    } else if (a.dtype == "<u4") {
      decode(std::uint32_t{});
    } else {
      c_.fail(a, fmt::format("dtype {} cannot hold counts", a.dtype));
    }
    return out;
  }

  /// Indices stored raw or relative to their group's base (local_array).
  template <class Visit>
  void indices(const InArray& a, const std::string& base, Index* out, Visit&& visit) {
    if (a.encoding == "raw") {
      expect(a, "<i4", "raw");
      if (a.bytes != 0) std::memcpy(out, a.data, a.bytes);
      return;
    }
    if (a.encoding != "local" || a.base != base) {
      c_.fail(a, fmt::format("encoding '{}' relative to '{}', expected raw or local to '{}'", a.encoding,
                             a.base, base));
    }
    bool ok = true;
    auto decode = [&]<class Stored>(Stored none) {
      visit([&](Index group_base, Index limit, std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
          Stored v;
          std::memcpy(&v, a.data + i * sizeof(Stored), sizeof v);
          ok &= v == none || Index{v} < limit;
          out[i] = v == none ? invalid_index : group_base + Index{v};
        }
      });
    };
    if (a.dtype == "|u1") {
      decode(std::uint8_t{0xff});
    } else if (a.dtype == "<u2") {
      decode(std::uint16_t{0xffff});
    } else {
      c_.fail(a, fmt::format("dtype {} cannot hold local indices", a.dtype));
    }
    if (!ok) c_.fail(a, "a local index lies beyond its element's nodes or regions");
  }

  [[noreturn]] void fail(const InArray& a, const std::string& what) const { c_.fail(a, what); }

 private:
  const Container& c_;
  const MapReadOptions& options_;
  std::thread::id caller_;
  std::atomic<std::uint64_t> done_ = 0;
};

template <int d>
std::shared_ptr<const Surface<d>> read_surface(const Container& c, MapArrayReader& r, const char* prefix,
                                               const MapReadOptions& options) {
  const std::string vertices_name = fmt::format("{}_vertices", prefix);
  const std::string elements_name = fmt::format("{}_elements", prefix);
  std::vector<WorldPoint<d>> vertices;
  std::vector<ElementCorners<d>> elements;
  r.raw(r.get(vertices_name, {d + 1}, r.rows(vertices_name)), "<f8", vertices);
  r.raw(r.get(elements_name, {d + 1}, r.rows(elements_name)), "<i4", elements);
  std::shared_ptr<const Surface<d>> surface;
  try {
    surface = std::make_shared<const Surface<d>>(std::move(vertices), std::move(elements));
  } catch (const InvalidSurfaceError& e) {
    throw InvalidSurfaceError(fmt::format("{}: {} surface: {}", c.file(), prefix, e.what()));
  }
  if (options.verify_checksums) {
    const auto it = c.toc().find(fmt::format("{}_fingerprint", prefix));
    if (it == c.toc().end() || !it->is_string() || *it != fingerprint_hex(surface_fingerprint(*surface))) {
      c.fail(fmt::format("the {} surface does not match the fingerprint in the table of contents "
                         "(the file is damaged)", prefix));
    }
  }
  return surface;
}

void check_begin(MapArrayReader& r, const InArray& a, const std::vector<Index>& begin, std::uint64_t size,
                 std::uint64_t total) {
  if (begin.size() != size || (size > 0 && static_cast<std::uint64_t>(begin.back()) != total) ||
      (size > 0 && begin.front() != 0)) {
    r.fail(a, fmt::format("does not describe the {} entries of the arrays it indexes", total));
  }
  for (std::size_t i = 0; i + 1 < begin.size(); ++i) {
    if (begin[i + 1] < begin[i]) r.fail(a, fmt::format("decreases at entry {}", i + 1));
  }
}

/// The region maps of a file that stores only the exceptions (add_region_maps): recomputed,
/// then the exceptions applied, then the whole compared with the writer's CRC-32.
template <int d>
void read_derived_region_maps(const Container& c, MapArrayReader& r, const Surface<d>& target, MapData<d>& m,
                              const MapReadOptions& options) {
  const auto info = c.toc().find("region_map");
  if (info == c.toc().end() || !info->is_object() || !info->contains("crc32") ||
      !(*info)["crc32"].is_number_unsigned()) {
    c.fail("the file has neither the array 'region_map' nor the table entry of derived region maps");
  }
  const std::size_t R = m.region_target.size(), N = m.node_position.size();
  bool corners_ok = true;
  for (const auto& corners : m.region_corners) {
    for (Index n : corners) corners_ok &= static_cast<std::size_t>(static_cast<std::uint32_t>(n)) < N;
  }
  if (!corners_ok) r.fail(c.array("region_corners"), "a region corner is not a node of the map");
  m.region_map.resize(R);
  std::vector<unsigned char> failed(R, 0);
  parallel_ranges(R, options.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t q = begin; q < end; ++q) {
      const std::optional<AffineMap<d>> derived = binary::derived_region_map(m, target, q);
      if (derived) {
        m.region_map[q] = *derived;
      } else {
        failed[q] = 1;
      }
    }
  });
  const auto bad = std::find(failed.begin(), failed.end(), 1);
  if (bad != failed.end()) {
    r.fail(c.array("region_target"), fmt::format("region {} names an S2 element that does not exist, or one of "
                                                 "its corners has such an image", bad - failed.begin()));
  }
  constexpr std::uint64_t D = d;
  const std::uint64_t E = r.rows("region_map_exception_region");
  std::vector<Index> regions;
  std::vector<AffineMap<d>> values;
  r.raw(r.get("region_map_exception_region", {}, E), "<i4", regions);
  r.raw(r.get("region_map_exception", {D + 1, D}, E), "<f8", values);
  for (std::size_t i = 0; i < E; ++i) {
    if (static_cast<std::size_t>(static_cast<std::uint32_t>(regions[i])) >= R) {
      r.fail(c.array("region_map_exception_region"), fmt::format("entry {} names region {}, which does not exist", i, regions[i]));
    }
    m.region_map[regions[i]] = values[i];
  }
  if (options.verify_checksums &&
      binary::crc32_parallel(m.region_map.data(), R * sizeof(AffineMap<d>), options.threads) !=
          (*info)["crc32"].get<std::uint64_t>()) {
    c.fail("the region maps recomputed from the nodes differ from the writer's (CRC-32 mismatch): the file "
           "is damaged, or was written on a machine whose floating-point arithmetic differs from this one's");
  }
}

/// The graph arrays of a map file that stores them all: segment maps, and version 1 files.
template <int d>
void read_graph_arrays(const Container& c, MapArrayReader& r, std::uint64_t T, std::uint64_t N,
                       const LocalGroups<d>& groups, MapData<d>& m) {
  {
    const InArray& a = r.get("neighbor_begin", {}, r.rows("neighbor_begin"));
    m.neighbor_begin = r.begin_array(a);
    check_begin(r, a, m.neighbor_begin, N + 1, r.rows("neighbor"));
  }
  const std::uint64_t M = r.rows("neighbor");
  m.neighbor.resize(M);
  r.indices(r.get("neighbor", {}, M), "node_begin", m.neighbor.data(), [&](auto&& f) { groups.neighbors(f); });
  r.raw(r.get("neighbor_edge_kind", {}, M), "|u1", m.neighbor_edge_kind);
  for (std::size_t i = 0; i < M; ++i) {
    if (static_cast<int>(m.neighbor_edge_kind[i]) > 1) {
      r.fail(c.array("neighbor_edge_kind"), fmt::format("entry {} is not 0 (closure) or 1 (target_edge)", i));
    }
  }

  {
    const InArray& begin = r.get("edge_node_begin", {}, r.rows("edge_node_begin"));
    m.edge_node_begin = r.begin_array(begin);
    const std::uint64_t K = r.rows("edge_node");
    m.edge_node.resize(K);
    const InArray& a = r.get("edge_node", {}, K);
    // Stored per element only in the d = 2 layout (3 ranges per element); d = 1 maps normally
    // have empty edge arrays, which are stored raw whatever they hold, as the text format does.
    if (a.encoding != "raw") check_begin(r, begin, m.edge_node_begin, 3 * T + 1, K);
    r.indices(a, "node_begin", m.edge_node.data(), [&](auto&& f) { groups.edge_nodes(f); });
  }

}

/// A version 2 triangle map's stored graph (add_stored_graph); PlMap checks its sizes and ranges.
StoredGraph read_stored_graph(MapArrayReader& r) {
  StoredGraph g;
  auto counts = [&](const char* name, std::vector<Index>& out) {
    const std::vector<Index> begin = r.begin_array(r.get(name, {}, r.rows(name)));
    out.resize(begin.empty() ? 0 : begin.size() - 1);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = begin[i + 1] - begin[i];
  };
  r.raw(r.get("graph_element", {}, r.rows("graph_element")), "<i4", g.element);
  counts("graph_neighbor_begin", g.neighbor_count);
  r.raw(r.get("graph_neighbor", {}, r.rows("graph_neighbor")), "<i4", g.neighbor);
  r.raw(r.get("graph_neighbor_edge_kind", {}, r.rows("graph_neighbor_edge_kind")), "|u1", g.neighbor_edge_kind);
  counts("graph_edge_node_begin", g.edge_node_count);
  r.raw(r.get("graph_edge_node", {}, r.rows("graph_edge_node")), "<i4", g.edge_node);
  r.raw(r.get("graph_region_neighbors", {3}, r.rows("graph_region_neighbors")), "<i4", g.region_neighbors);
  return g;
}

/// Decodes the map's arrays (everything but the surfaces and the derived region maps) into `m`;
/// `T` is the number of S1 elements.
template <int d>
void read_map_arrays(const Container& c, MapArrayReader& r, std::uint64_t T, bool with_graph, MapData<d>& m) {
  constexpr std::uint64_t D = d;
  {
    const InArray& a = r.get("node_begin", {}, r.rows("node_begin"));
    m.node_begin = r.begin_array(a);
    check_begin(r, a, m.node_begin, T + 1, r.rows("node_type"));
  }
  const std::uint64_t N = r.rows("node_type");
  r.raw(r.get("node_type", {}, N), "|u1", m.node_type);
  for (std::size_t n = 0; n < N; ++n) {
    if (static_cast<int>(m.node_type[n]) >= node_type_count) {
      r.fail(c.array("node_type"), fmt::format("node {} has unknown type {}", n, static_cast<int>(m.node_type[n])));
    }
  }
  r.raw(r.get("node_location", {}, N), "|i1", m.node_location);
  r.raw(r.get("node_position", {D}, N), "<f8", m.node_position);
  r.raw(r.get("node_image_element", {}, N), "<i4", m.node_image_element);
  r.raw(r.get("node_image_local", {D}, N), "<f8", m.node_image_local);
  r.raw(r.get("node_target", {}, N), "<i4", m.node_target);

  const LocalGroups<d> groups{m, T};
  if (with_graph) read_graph_arrays(c, r, T, N, groups, m);
  {
    const InArray& a = r.get("region_begin", {}, r.rows("region_begin"));
    m.region_begin = r.begin_array(a);
    check_begin(r, a, m.region_begin, T + 1, r.rows("region_target"));
  }
  const std::uint64_t R = r.rows("region_target");
  m.region_corners.resize(R);
  if (with_graph) m.region_neighbors.resize(R);
  r.indices(r.get("region_corners", {D + 1}, R), "node_begin", scalars<Index>(m.region_corners),
            [&](auto&& f) { groups.region_corners(f); });
  if (with_graph) {
    r.indices(r.get("region_neighbors", {D + 1}, R), "region_begin", scalars<Index>(m.region_neighbors),
              [&](auto&& f) { groups.region_neighbors(f); });
  } else {
    m.region_neighbors.clear();
  }
  r.raw(r.get("region_target", {}, R), "<i4", m.region_target);
  if (c.has("region_map")) r.raw(r.get("region_map", {D + 1, D}, R), "<f8", m.region_map);
  m.start_region.resize(T);
  r.indices(r.get("start_region", {}, T), "region_begin", m.start_region.data(),
            [&](auto&& f) { groups.start_region(f); });
}

template <int d>
PlMap<d> read_map(const Container& c, int orientation, MapProvenance provenance, const MapReadOptions& options) {
  if (options.verify_checksums) c.verify_all_checksums(options.threads);
  MapArrayReader r(c, options);
  std::shared_ptr<const Surface<d>> domain, target;
  MapData<d> m;
  m.orientation = orientation;
  // The two surfaces (checks, adjacency, fingerprint) and the map's arrays are independent work,
  // done side by side. If several are damaged, the error that reaches the caller is the first in
  // this order (domain, target, arrays), whatever the thread count.
  const std::uint64_t T = r.rows("domain_elements");
  // Version 2 stores a triangle map's graph only for the elements that keep it (PlMap's stored
  // form); segment maps and version 1 files store all graph arrays.
  const bool stored_form = d == 2 && c.version() >= 2;
  StoredGraph graph;
  parallel_for_pieces_of_size(3, 1, options.threads, [&](std::size_t piece, std::size_t, std::size_t) {
    if (piece == 0) {
      domain = read_surface<d>(c, r, "domain", options);
    } else if (piece == 1) {
      target = read_surface<d>(c, r, "target", options);
    } else {
      read_map_arrays<d>(c, r, T, !stored_form, m);
      if (stored_form) graph = read_stored_graph(r);
    }
  });
  if (!c.has("region_map")) read_derived_region_maps(c, r, *target, m, options);

  // From here on the checks of a text map: the same constructor and structural validation.
  try {
    PlMap<d> map = [&] {
      if constexpr (d == 2) {
        if (stored_form) return PlMap<2>(std::move(domain), std::move(target), std::move(m), std::move(graph));
      }
      return PlMap<d>(std::move(domain), std::move(target), std::move(m));
    }();
    validate_map_structure(map, options.threads);
    map.set_provenance(std::move(provenance));
    return map;
  } catch (const InvalidMapError& e) {
    throw InvalidMapError(fmt::format("{}: {}", c.file(), e.what()));
  }
}

}  // namespace

bool has_binary_map_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == binary_map_extension;
}

bool looks_like_binary_map(std::string_view head) { return head.starts_with(binary_map_magic); }

template <int d>
void write_binary_map(std::ostream& out, const PlMap<d>& map, const MapWriteOptions& options) {
  nlohmann::json toc = binary::map_table_header(map);
  const std::vector<OutArray> arrays = map_arrays(map, toc, options.threads);
  binary::write_container(out, std::move(toc), arrays, options.progress, options.threads);
}

AnyPlMap parse_binary_map(std::string_view content, const std::string& source_name, const MapReadOptions& options) {
  const Container c(content, source_name, options.verify_checksums);
  binary::MapTableHeader h = binary::read_map_table_header(c.toc(), source_name);
  if (h.dimension == 1) return read_map<1>(c, h.orientation, std::move(h.provenance), options);
  return read_map<2>(c, h.orientation, std::move(h.provenance), options);
}

int binary_map_file_dimension(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(binary::header_bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::uint64_t table = Container::table_bytes_from_header(head, path.string());
  head.resize(binary::header_bytes + table);
  in.read(head.data() + binary::header_bytes, static_cast<std::streamsize>(table));
  head.resize(binary::header_bytes + static_cast<std::size_t>(in.gcount()));
  return binary::read_map_table_header(Container::table_only(head, path.string()), path.string()).dimension;
}

template void write_binary_map<1>(std::ostream&, const PlMap<1>&, const MapWriteOptions&);
template void write_binary_map<2>(std::ostream&, const PlMap<2>&, const MapWriteOptions&);

}  // namespace plmap
