// Wavefront OBJ reader. Hand-written rather than using libtinyobjloader-dev: tinyobjloader
// reports problems as free-form warning strings, accepts out-of-range indices in some paths and
// triangulates on its own terms; plmap needs every error typed and located (file + line).
#include "surface_parse_support.hpp"

namespace plmap::surface_io_detail {

namespace {

/// Parses one face corner "v", "v/vt", "v//vn" or "v/vt/vn" and returns the vertex part.
std::int64_t corner_vertex(const Cursor& cursor, std::string_view token) {
  const std::size_t slash = token.find('/');
  const std::string_view vertex = token.substr(0, slash);
  std::int64_t v;
  if (!parse_integer(vertex, v) || v == 0)
    cursor.fail_at(token, fmt::format("bad face corner '{}': expected a non-zero vertex index",
                                      token.substr(0, 40)));
  if (slash != std::string_view::npos) {
    // Texture and normal indices are not used, but they must still be well-formed.
    std::string_view rest = token.substr(slash + 1);
    int parts = 1;
    while (true) {
      const std::size_t next = rest.find('/');
      const std::string_view part = rest.substr(0, next);
      std::int64_t ignored;
      if (!part.empty() && !parse_integer(part, ignored))
        cursor.fail_at(token, fmt::format("bad face corner '{}'", token.substr(0, 40)));
      if (++parts > 3) cursor.fail_at(token, fmt::format("bad face corner '{}'", token.substr(0, 40)));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }
  return v;
}

/// Statements that carry nothing a triangle surface is made of, skipped on purpose: texture and
/// normal data, grouping, materials and display attributes, points and polylines (no area), and
/// free-form curves (their control points and parameters, which belong to curves).
bool is_skipped_statement(std::string_view keyword) {
  static constexpr std::string_view skipped[] = {
      "vt", "vn", "vp", "p", "l", "g", "o", "s", "mg", "usemtl", "mtllib", "usemap", "maplib",
      "lod", "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech",
      "cstype", "deg", "bmat", "step", "curv", "curv2", "parm", "trim", "hole", "scrv", "sp",
      "end", "con"};
  return std::find(std::begin(skipped), std::end(skipped), keyword) != std::end(skipped);
}

}  // namespace

RawMesh<2> parse_obj(Cursor& cursor, const SurfaceReadOptions& options) {
  RawMesh<2> mesh;
  std::string_view line;
  std::vector<Index> corners;
  while (cursor.read_content_line(line)) {
    Tokens t(line);
    const std::string_view keyword = t.next();
    if (keyword == "v") {
      WorldPoint<2> p;
      for (int k = 0; k < 3; ++k) p(k) = read_coordinate(cursor, t.next(), "a vertex coordinate");
      // An optional weight or vertex colour (RGB, RGBA) may follow; plmap ignores them. More
      // numbers than that mean several vertices on one line, which must not vanish.
      const std::size_t extras = t.count();
      if (extras > 4)
        cursor.fail_at(line, fmt::format("vertex has {} numbers after its coordinates; a weight or "
                                         "colour has at most 4 (one vertex per 'v' line)",
                                         extras));
      for (std::string_view extra = t.next(); !extra.empty(); extra = t.next())
        read_coordinate(cursor, extra, "a vertex weight or colour component");
      mesh.vertices.push_back(p);
    } else if (keyword == "f" || keyword == "fo") {  // "fo" is the old name of "f"
      corners.clear();
      const auto nv = static_cast<std::int64_t>(mesh.vertices.size());
      for (std::string_view token = t.next(); !token.empty(); token = t.next()) {
        const std::int64_t v = corner_vertex(cursor, token);
        // Negative indices count back from the latest vertex. Positive ones may in principle
        // refer forward, so they are range-checked once the whole file is read.
        const std::int64_t zero_based = v > 0 ? v - 1 : nv + v;
        if (v < 0 && zero_based < 0)
          cursor.fail_at(token, fmt::format("relative index {} reaches before the first vertex "
                                            "({} vertices so far)", v, nv));
        corners.push_back(narrow_index(zero_based));
        if (corners.back() < 0)
          cursor.fail_at(token, fmt::format("vertex index {} is out of range", v));
      }
      add_polygon(cursor, cursor.offset_of(line), corners, options, mesh);
    } else if (keyword == "surf") {
      // A free-form surface would be part of the surface; plmap reads polygons only.
      cursor.fail_at(line, "free-form surface ('surf') is not supported; export the surface as "
                           "polygons ('f')");
    } else if (keyword == "call") {
      cursor.fail_at(line, "'call' (reading another file) is not supported; merge the files first");
    } else if (!is_skipped_statement(keyword)) {
      // Anything else is corruption or an extension plmap does not know: it might carry
      // geometry, so it is refused rather than skipped.
      cursor.fail_at(line, fmt::format("unknown OBJ statement '{}'", keyword.substr(0, 40)));
    }
  }
  check_elements(cursor, mesh, VertexNumbering::one_based);
  return mesh;
}

}  // namespace plmap::surface_io_detail
