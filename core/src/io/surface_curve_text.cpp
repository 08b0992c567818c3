// plmap's curve text format (.curve); the specification is in docs/surface-formats.md.
#include "surface_parse_support.hpp"

namespace plmap::surface_io_detail {

namespace {

/// Reads "<keyword> <count>"; `noun` names one item in messages ("vertex count 5 ...").
std::size_t read_section_count(Cursor& cursor, std::string_view keyword, std::string_view noun) {
  std::string_view line;
  if (!cursor.read_content_line(line))
    cursor.fail(fmt::format("file ends where '{} <count>' was expected", keyword));
  Tokens t(line);
  const std::string_view word = t.next();
  if (word != keyword)
    cursor.fail_at(word, fmt::format("expected '{} <count>', found '{}'", keyword, word.substr(0, 40)));
  const std::string_view count = t.next();
  const std::int64_t n = read_integer(cursor, count, fmt::format("the {} count", noun));
  if (!t.empty()) cursor.fail_at(line, fmt::format("unexpected text after the {} count", noun));
  return checked_count(cursor, cursor.offset_of(count), n, 2, noun);
}

}  // namespace

RawMesh<1> parse_curve_text(Cursor& cursor, const SurfaceReadOptions&) {
  RawMesh<1> mesh;
  std::string_view line;
  if (!cursor.read_content_line(line)) cursor.fail("empty file: expected 'plmap-curve 1'");
  {
    Tokens t(line);
    const std::string_view magic = t.next();
    if (magic != "plmap-curve")
      cursor.fail_at(magic, fmt::format("expected 'plmap-curve 1', found '{}'", magic.substr(0, 40)));
    const std::string_view version = t.next();
    if (version != "1")
      cursor.fail_at(version, fmt::format("unsupported curve format version '{}'", version.substr(0, 40)));
    if (!t.empty()) cursor.fail_at(line, "unexpected text after the version");
  }
  const std::size_t nv = read_section_count(cursor, "vertices", "vertex");
  mesh.vertices.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    if (!cursor.read_content_line(line)) cursor.fail(fmt::format("file ends after {} of {} vertices", i, nv));
    Tokens t(line);
    WorldPoint<1> p;
    for (int k = 0; k < 2; ++k) p(k) = read_coordinate(cursor, t.next(), "a vertex coordinate");
    if (!t.empty()) cursor.fail_at(line, fmt::format("vertex {} has more than 2 coordinates", i));
    mesh.vertices.push_back(p);
  }
  const std::size_t ns = read_section_count(cursor, "segments", "segment");
  mesh.elements.reserve(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    if (!cursor.read_content_line(line)) cursor.fail(fmt::format("file ends after {} of {} segments", s, ns));
    Tokens t(line);
    ElementCorners<1> corners;
    for (int k = 0; k < 2; ++k) corners[k] = narrow_index(read_integer(cursor, t.next(), "a vertex index"));
    if (!t.empty()) cursor.fail_at(line, fmt::format("segment {} has more than 2 vertices", s));
    mesh.elements.push_back(corners);
    mesh.element_offset.push_back(cursor.offset_of(line));
  }
  if (cursor.read_content_line(line)) cursor.fail_at(line, "unexpected text after the last segment");
  check_elements(cursor, mesh, VertexNumbering::zero_based);
  return mesh;
}

}  // namespace plmap::surface_io_detail
