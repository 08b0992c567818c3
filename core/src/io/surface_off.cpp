// OFF reader. Hand-written: no maintained Debian package parses OFF on its own, and the
// readers share one error discipline (file + line, bounded counts) that a wrapper could not give.
#include "surface_parse_support.hpp"

#include <plmap/core/huge_page_allocator.hpp>

namespace plmap::surface_io_detail {

namespace {

/// Recognises the OFF header keyword: [ST][C][N]OFF. Returns false for other words; throws for
/// the variants plmap cannot use (4OFF: 4-D points, nOFF: arbitrary dimension).
bool is_off_keyword(const Cursor& cursor, std::string_view token, bool& has_extras) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  std::string_view prefix = token.substr(0, token.size() - 3);
  has_extras = !prefix.empty();
  if (prefix.starts_with("ST")) prefix.remove_prefix(2);
  if (prefix.starts_with("C")) prefix.remove_prefix(1);
  if (prefix.starts_with("N")) prefix.remove_prefix(1);
  if (prefix.starts_with("4") || prefix.starts_with("n"))
    cursor.fail_at(token, fmt::format("'{}': only 3-D OFF files are supported", token));
  if (!prefix.empty()) cursor.fail_at(token, fmt::format("unknown OFF header '{}'", token));
  return true;
}

}  // namespace

RawMesh<2> parse_off(Cursor& cursor, const SurfaceReadOptions& options) {
  RawMesh<2> mesh;
  std::string_view line;
  if (!cursor.read_content_line(line)) cursor.fail("empty file: expected an OFF header");
  Tokens tokens(line);
  std::string_view first = tokens.next();
  bool has_extras = false;
  if (is_off_keyword(cursor, first, has_extras)) {
    // The counts may follow the keyword on the same line ("OFF 8 6 0") or on the next one.
    if (tokens.empty()) {
      if (!cursor.read_content_line(line))
        cursor.fail("file ends after the OFF header: expected vertex and face counts");
      tokens = Tokens(line);
    }
    first = tokens.next();
  }
  // The header keyword is optional in OFF, so `first` is the vertex count.
  const std::int64_t nv_read = read_integer(cursor, first, "the vertex count");
  const std::string_view nf_token = tokens.next();
  const std::int64_t nf_read = read_integer(cursor, nf_token, "the face count");
  // Every vertex and face takes at least one line of two bytes.
  const std::size_t nv = checked_count(cursor, cursor.offset_of(first), nv_read, 2, "vertex");
  const std::size_t nf = checked_count(cursor, cursor.offset_of(nf_token), nf_read, 2, "face");

  // the room is backed ahead of the appends (a header's counts are checked against the file's
  // size only, so not all at once)
  PagesBackedAhead vertices_backing, elements_backing, offsets_backing;
  mesh.vertices.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    if (!cursor.read_content_line(line))
      cursor.fail(fmt::format("file ends after {} of {} vertices", i, nv));
    Tokens t(line);
    WorldPoint<2> p;
    for (int k = 0; k < 3; ++k) p(k) = read_coordinate(cursor, t.next(), "a vertex coordinate");
    // Colour, normal and texture variants carry extra numbers per vertex; plain OFF does not,
    // so extra numbers there mean the counts or the dimension are wrong.
    if (!has_extras && !t.empty())
      cursor.fail_at(line, fmt::format("vertex {} has more than 3 coordinates", i));
    vertices_backing.before_append(mesh.vertices);
    mesh.vertices.push_back(p);
  }

  mesh.elements.reserve(nf);
  mesh.element_offset.reserve(nf);
  std::vector<Index> corners;
  for (std::size_t f = 0; f < nf; ++f) {
    if (!cursor.read_content_line(line))
      cursor.fail(fmt::format("file ends after {} of {} faces", f, nf));
    Tokens t(line);
    const std::string_view count_token = t.next();
    const std::int64_t n = read_integer(cursor, count_token, "the face's vertex count");
    if (n < 0 || static_cast<std::uint64_t>(n) > line.size())
      cursor.fail_at(line, fmt::format("face {} claims {} vertices", f, n));
    corners.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t v = read_integer(cursor, t.next(), "a vertex index");
      if (v < 0 || v >= static_cast<std::int64_t>(nv))
        cursor.fail_at(line, fmt::format("face {} refers to vertex {}, but there are {} vertices",
                                         f, v, nv));
      corners.push_back(static_cast<Index>(v));
    }
    // Anything after the indices is a face colour (a colour-map index, or RGB or RGBA), which
    // plmap ignores. More than that is not a colour: the face's vertex count is wrong or two
    // faces share a line, and ignoring the rest would drop data.
    const std::size_t extras = t.count();
    if (extras > 4)
      cursor.fail_at(line, fmt::format("face {} has {} numbers after its {} vertex indices; a face "
                                       "colour has at most 4 (is its vertex count wrong?)",
                                       f, extras, n));
    for (std::string_view colour = t.next(); !colour.empty(); colour = t.next())
      read_coordinate(cursor, colour, "a face colour component");
    const std::size_t triangles = corners.size() >= 3 ? corners.size() - 2 : 0;
    elements_backing.before_append(mesh.elements, triangles);
    offsets_backing.before_append(mesh.element_offset, triangles);
    add_polygon(cursor, cursor.offset_of(line), corners, options, mesh);
  }
  // Data after the announced faces would otherwise be ignored: the counts are wrong.
  if (cursor.read_content_line(line))
    cursor.fail_at(line, fmt::format("unexpected line after the {} faces the header announces "
                                     "(is the face count wrong?)",
                                     nf));
  check_elements(cursor, mesh, VertexNumbering::zero_based);
  return mesh;
}

}  // namespace plmap::surface_io_detail

