// STL reader (ASCII and binary). STL stores each facet's three corners separately; corners with
// exactly equal coordinates are merged into one vertex, numbered in order of first appearance.
// No tolerance is applied: merging nearby points would change the surface's combinatorics in a
// way the caller did not ask for.
#include "surface_parse_support.hpp"

#include <map>

namespace plmap::surface_io_detail {

namespace {

constexpr std::size_t binary_header_bytes = 80;
constexpr std::size_t binary_facet_bytes = 50;  // normal, 3 corners (12 floats), attribute

/// Case-insensitive keyword comparison ("facet", "FACET").
bool keyword_is(std::string_view token, std::string_view keyword) {
  return token.size() == keyword.size() &&
         std::equal(token.begin(), token.end(), keyword.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

class VertexMerger {
 public:
  explicit VertexMerger(RawMesh<2>& mesh) : mesh_(mesh) {}
  Index index_of(const WorldPoint<2>& p) {
    // std::map's ordering treats -0.0 and 0.0 as equal, which is what "same point" means.
    const std::array<double, 3> key{p(0), p(1), p(2)};
    const auto [it, inserted] = index_.try_emplace(key, static_cast<Index>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }

 private:
  RawMesh<2>& mesh_;
  std::map<std::array<double, 3>, Index> index_;
};

void expect_keyword(Cursor& cursor, std::string_view keyword) {
  const std::string_view token = cursor.read_token();
  if (!keyword_is(token, keyword))
    cursor.fail_at(token, token.empty()
                              ? fmt::format("file ends where '{}' was expected", keyword)
                              : fmt::format("expected '{}', found '{}'", keyword, token.substr(0, 40)));
}

/// Reads the rest of a 'solid' or 'endsolid' line (the solid's name). A facet that starts on
/// that line would be swallowed with the name, so the file is refused instead.
void skip_solid_name(Cursor& cursor) {
  std::string_view line;
  cursor.read_line(line);
  Tokens t(line);
  for (std::string_view token = t.next(); !token.empty(); token = t.next())
    if (keyword_is(token, "facet"))
      cursor.fail_at(token, "'facet' on the line of 'solid' or 'endsolid'; each facet must start "
                            "on a line of its own");
}

RawMesh<2> parse_ascii(Cursor& cursor) {
  RawMesh<2> mesh;
  VertexMerger merger(mesh);
  bool any_solid = false;
  // A file may hold several solids one after the other; they are read into one surface.
  while (true) {
    const std::string_view solid = cursor.read_token();
    if (solid.empty()) break;
    if (!keyword_is(solid, "solid"))
      cursor.fail_at(solid, fmt::format("expected 'solid', found '{}'", solid.substr(0, 40)));
    any_solid = true;
    skip_solid_name(cursor);
    while (true) {
      const std::string_view token = cursor.read_token();
      if (keyword_is(token, "endsolid")) {
        skip_solid_name(cursor);  // the name again
        break;
      }
      if (!keyword_is(token, "facet"))
        cursor.fail_at(token, token.empty() ? std::string("file ends inside a solid (no 'endsolid')")
                                            : fmt::format("expected 'facet' or 'endsolid', found '{}'",
                                                          token.substr(0, 40)));
      const std::size_t facet_offset = cursor.offset_of(token);
      expect_keyword(cursor, "normal");
      for (int k = 0; k < 3; ++k) {
        // The normal is recomputed by anyone who needs it; it only has to be a number.
        const std::string_view n = cursor.read_token();
        double ignored;
        if (!parse_double(n, ignored))
          cursor.fail_at(n, fmt::format("expected a normal component, found '{}'", n.substr(0, 40)));
      }
      expect_keyword(cursor, "outer");
      expect_keyword(cursor, "loop");
      ElementCorners<2> corners{};
      for (int c = 0; c < 3; ++c) {
        expect_keyword(cursor, "vertex");
        WorldPoint<2> p;
        for (int k = 0; k < 3; ++k)
          p(k) = read_coordinate(cursor, cursor.read_token(), "a vertex coordinate");
        corners[c] = merger.index_of(p);
      }
      const std::string_view end_loop = cursor.read_token();
      if (keyword_is(end_loop, "vertex"))
        cursor.fail_at(end_loop, "facet with more than 3 vertices; STL facets are triangles");
      if (!keyword_is(end_loop, "endloop"))
        cursor.fail_at(end_loop, fmt::format("expected 'endloop', found '{}'", end_loop.substr(0, 40)));
      expect_keyword(cursor, "endfacet");
      mesh.elements.push_back(corners);
      mesh.element_offset.push_back(facet_offset);
    }
  }
  if (!any_solid) cursor.fail("empty file: expected 'solid'");
  return mesh;
}

RawMesh<2> parse_binary(Cursor& cursor) {
  cursor.use_byte_locations();
  RawMesh<2> mesh;
  VertexMerger merger(mesh);
  cursor.skip(binary_header_bytes, "the 80-byte STL header");
  const std::size_t count_at = cursor.position();
  const auto count = cursor.read_binary<std::uint32_t>(false, "the facet count");
  const std::size_t n = checked_count(cursor, count_at, count, binary_facet_bytes, "facet");
  mesh.elements.reserve(n);
  mesh.element_offset.reserve(n);
  for (std::size_t f = 0; f < n; ++f) {
    const std::size_t facet_at = cursor.position();
    cursor.skip(12, "a facet normal");
    ElementCorners<2> corners{};
    for (int c = 0; c < 3; ++c) {
      WorldPoint<2> p;
      for (int k = 0; k < 3; ++k) {
        const std::size_t at = cursor.position();
        p(k) = cursor.read_binary<float>(false, "a vertex coordinate");
        check_finite(cursor, at, p(k), fmt::format("a coordinate of facet {}", f));
      }
      corners[c] = merger.index_of(p);
    }
    cursor.skip(2, "a facet attribute");
    mesh.elements.push_back(corners);
    mesh.element_offset.push_back(facet_at);
  }
  // Facets after the announced count would otherwise be ignored (a larger count is caught by
  // checked_count above). Stray bytes that cannot be a facet mean a corrupted file just as well.
  if (const std::size_t extra = cursor.remaining(); extra >= binary_facet_bytes)
    cursor.fail(fmt::format("the header's facet count is {}, but {} more bytes follow those facets "
                            "(room for {} more): the count is wrong",
                            n, extra, extra / binary_facet_bytes));
  else if (extra > 0)
    cursor.fail(fmt::format("{} stray bytes follow the last facet (the header's facet count is {})",
                            extra, n));
  return mesh;
}

}  // namespace

bool stl_is_binary(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && is_space(data[i])) ++i;
  const bool starts_with_solid = data.substr(i, 5) == "solid";
  if (data.size() >= binary_header_bytes + 4) {
    std::uint32_t count = 0;  // little endian, whatever the machine's order
    for (int b = 3; b >= 0; --b)
      count = (count << 8) | static_cast<unsigned char>(data[binary_header_bytes + b]);
    const std::uint64_t expected =
        binary_header_bytes + 4 + static_cast<std::uint64_t>(count) * binary_facet_bytes;
    if (expected == data.size()) return true;
    // A binary file whose header starts with "solid" and whose count is wrong: ASCII STL never
    // holds a NUL byte, binary facets nearly always do (zero coordinates, attribute bytes). Read
    // as binary, the wrong count is reported as such instead of as garbled ASCII.
    if (starts_with_solid && data.find('\0', binary_header_bytes) != std::string_view::npos) return true;
  }
  return !starts_with_solid;
}

RawMesh<2> parse_stl(Cursor& cursor, const SurfaceReadOptions&) {
  RawMesh<2> mesh = stl_is_binary(cursor.data()) ? parse_binary(cursor) : parse_ascii(cursor);
  check_elements(cursor, mesh, VertexNumbering::internal);
  return mesh;
}

}  // namespace plmap::surface_io_detail
