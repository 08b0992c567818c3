// PLY reader (ASCII, binary little endian, binary big endian). Hand-written: tinyply and happly
// are not packaged for Debian, and a generic PLY library would still need the checks below
// (counts bounded by file size, located errors) around it.
#include "surface_parse_support.hpp"

#include <optional>

namespace plmap::surface_io_detail {

namespace {

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<Scalar> scalar_from_name(std::string_view name) {
  if (name == "char" || name == "int8") return Scalar::int8;
  if (name == "uchar" || name == "uint8") return Scalar::uint8;
  if (name == "short" || name == "int16") return Scalar::int16;
  if (name == "ushort" || name == "uint16") return Scalar::uint16;
  if (name == "int" || name == "int32") return Scalar::int32;
  if (name == "uint" || name == "uint32") return Scalar::uint32;
  if (name == "float" || name == "float32") return Scalar::float32;
  if (name == "double" || name == "float64") return Scalar::float64;
  return std::nullopt;
}

std::size_t scalar_bytes(Scalar s) {
  switch (s) {
    case Scalar::int8:
    case Scalar::uint8: return 1;
    case Scalar::int16:
    case Scalar::uint16: return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32: return 4;
    case Scalar::float64: return 8;
  }
  return 1;
}

bool is_index_list_name(std::string_view name) {
  return name == "vertex_indices" || name == "vertex_index";
}

bool is_integral(Scalar s) { return s != Scalar::float32 && s != Scalar::float64; }

struct Property {
  std::string name;
  bool is_list = false;
  Scalar count_type = Scalar::uint8;  // lists only
  Scalar value_type = Scalar::float32;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::size_t header_offset = 0;
  std::vector<Property> properties;
};

enum class Layout { ascii, binary_little, binary_big };

/// Reads property values one at a time, as doubles, from ASCII or binary data.
class ValueReader {
 public:
  ValueReader(Cursor& cursor, Layout layout) : cursor_(cursor), layout_(layout) {}

  /// Reads a value of type s; `at` receives its offset (for messages).
  double read(Scalar s, std::size_t& at, std::string_view what) {
    if (layout_ == Layout::ascii) {
      const std::string_view token = cursor_.read_token();
      at = cursor_.offset_of(token);
      if (token.empty()) cursor_.fail_at(at, fmt::format("file ends where {} was expected", what));
      double value;
      if (!parse_double(token, value))
        cursor_.fail_at(at, fmt::format("expected {}, found '{}'", what, token.substr(0, 40)));
      if (is_integral(s) && value != std::floor(value))
        cursor_.fail_at(at, fmt::format("expected an integer for {}, found '{}'", what,
                                        token.substr(0, 40)));
      return value;
    }
    at = cursor_.position();
    const bool big = layout_ == Layout::binary_big;
    switch (s) {
      case Scalar::int8: return cursor_.read_binary<std::int8_t>(big, what);
      case Scalar::uint8: return cursor_.read_binary<std::uint8_t>(big, what);
      case Scalar::int16: return cursor_.read_binary<std::int16_t>(big, what);
      case Scalar::uint16: return cursor_.read_binary<std::uint16_t>(big, what);
      case Scalar::int32: return cursor_.read_binary<std::int32_t>(big, what);
      case Scalar::uint32: return cursor_.read_binary<std::uint32_t>(big, what);
      case Scalar::float32: return cursor_.read_binary<float>(big, what);
      case Scalar::float64: return cursor_.read_binary<double>(big, what);
    }
    return 0.0;
  }

  /// Reads a list length, bounded by the bytes that remain.
  std::size_t read_list_length(const Property& p) {
    std::size_t at = 0;
    const double n = read(p.count_type, at, "a list length");
    if (!(n >= 0) || n > static_cast<double>(std::numeric_limits<Index>::max()))
      cursor_.fail_at(at, fmt::format("bad list length {} for property '{}'", n, p.name));
    const std::size_t min_bytes = layout_ == Layout::ascii ? 2 : scalar_bytes(p.value_type);
    return checked_count(cursor_, at, static_cast<std::int64_t>(n), min_bytes, "list entry");
  }

 private:
  Cursor& cursor_;
  Layout layout_;
};

/// Smallest number of bytes one record of the element can take.
std::size_t min_record_bytes(const Element& e, Layout layout) {
  std::size_t bytes = 0;
  for (const Property& p : e.properties)
    // An ASCII value takes at least one character (the separators are shared).
    bytes += layout == Layout::ascii ? 1 : scalar_bytes(p.is_list ? p.count_type : p.value_type);
  return bytes;
}

struct Header {
  Layout layout = Layout::ascii;
  std::vector<Element> elements;
};

/// One 'property' line (after the keyword), for the element declared last.
Property read_property(Cursor& cursor, std::string_view line, Tokens& t, const Element& element) {
  Property p;
  std::string_view type = t.next();
  if (type == "list") {
    p.is_list = true;
    const std::string_view count_type = t.next();
    const auto c = scalar_from_name(count_type);
    if (!c || !is_integral(*c)) cursor.fail_at(line, fmt::format("bad list count type '{}'", count_type.substr(0, 40)));
    p.count_type = *c;
    type = t.next();
  }
  const auto v = scalar_from_name(type);
  if (!v) cursor.fail_at(line, fmt::format("unknown property type '{}'", type.substr(0, 40)));
  p.value_type = *v;
  p.name = std::string(t.next());
  if (p.name.empty()) cursor.fail_at(line, "property without a name");
  // With two properties of one name, which one holds the data is a guess.
  for (const Property& other : element.properties)
    if (other.name == p.name)
      cursor.fail_at(line, fmt::format("duplicate property '{}' in element '{}'", p.name.substr(0, 40),
                                       element.name.substr(0, 40)));
  return p;
}

/// The header, from the line after 'ply' to 'end_header'.
Header read_header(Cursor& cursor) {
  std::string_view line;
  std::optional<Layout> layout;
  Header header;
  bool ended = false;
  while (cursor.read_line(line)) {
    Tokens t(line);
    const std::string_view keyword = t.next();
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      ended = true;
      break;
    }
    if (keyword == "format") {
      const std::string_view kind = t.next();
      const std::string_view version = t.next();
      if (version != "1.0") cursor.fail_at(line, fmt::format("unsupported PLY version '{}'", version));
      if (kind == "ascii") layout = Layout::ascii;
      else if (kind == "binary_little_endian") layout = Layout::binary_little;
      else if (kind == "binary_big_endian") layout = Layout::binary_big;
      else cursor.fail_at(line, fmt::format("unknown PLY format '{}'", kind.substr(0, 40)));
    } else if (keyword == "element") {
      Element e;
      e.name = std::string(t.next());
      const std::string_view count_token = t.next();
      const std::int64_t count = read_integer(cursor, count_token, "the element count");
      if (count < 0) cursor.fail_at(count_token, "negative element count");
      if (e.name.empty()) cursor.fail_at(line, "element without a name");
      e.count = static_cast<std::size_t>(count);  // bounded once the data size is known
      e.header_offset = cursor.offset_of(count_token);
      header.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (header.elements.empty()) cursor.fail_at(line, "property before any element");
      header.elements.back().properties.push_back(read_property(cursor, line, t, header.elements.back()));
    } else {
      cursor.fail_at(line, fmt::format("unknown PLY header line '{}'", line.substr(0, 40)));
    }
  }
  if (!ended) cursor.fail("file ends inside the header (no 'end_header')");
  if (!layout) cursor.fail_at(0, "the header has no 'format' line");
  header.layout = *layout;
  return header;
}

/// The 'vertex' element's `count` records: x, y and z of each, the other properties skipped.
void read_vertices(Cursor& cursor, ValueReader& reader, const Element& e, std::size_t count, RawMesh<2>& mesh) {
  int xyz[3] = {-1, -1, -1};
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (e.properties[i].name == std::string(1, static_cast<char>('x' + k)) && !e.properties[i].is_list)
        xyz[k] = static_cast<int>(i);
  for (int k = 0; k < 3; ++k)
    if (xyz[k] < 0)
      cursor.fail_at(e.header_offset,
                     fmt::format("the vertex element has no scalar property '{}'", static_cast<char>('x' + k)));
  mesh.vertices.reserve(count);
  for (std::size_t v = 0; v < count; ++v) {
    WorldPoint<2> p = WorldPoint<2>::Zero();
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const Property& prop = e.properties[i];
      std::size_t at = 0;
      if (prop.is_list) {
        const std::size_t n = reader.read_list_length(prop);
        for (std::size_t j = 0; j < n; ++j) reader.read(prop.value_type, at, "a list entry");
        continue;
      }
      const double value = reader.read(prop.value_type, at, "a vertex property");
      for (int k = 0; k < 3; ++k)
        if (xyz[k] == static_cast<int>(i)) {
          check_finite(cursor, at, value, fmt::format("coordinate {} of vertex {}", static_cast<char>('x' + k), v));
          p(k) = value;
        }
    }
    mesh.vertices.push_back(p);
  }
}

/// The 'face' element's `count` records: the vertex index list of each, as a polygon of the
/// mesh, the other properties skipped.
void read_faces(Cursor& cursor, ValueReader& reader, const Element& e, std::size_t count,
                const SurfaceReadOptions& options, RawMesh<2>& mesh) {
  int list = -1;
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i].is_list && is_index_list_name(e.properties[i].name)) {
      if (list >= 0)
        cursor.fail_at(e.header_offset, "the face element has both 'vertex_indices' and "
                                        "'vertex_index'; which one holds the faces is unclear");
      list = static_cast<int>(i);
    }
  if (list < 0) cursor.fail_at(e.header_offset, "the face element has no list property 'vertex_indices'");
  if (!is_integral(e.properties[static_cast<std::size_t>(list)].value_type))
    cursor.fail_at(e.header_offset, "face vertex indices must have an integer type");
  std::vector<Index> corners;
  mesh.elements.reserve(count);
  for (std::size_t f = 0; f < count; ++f) {
    std::size_t face_at = cursor.position();
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const Property& prop = e.properties[i];
      std::size_t at = 0;
      if (!prop.is_list) {
        reader.read(prop.value_type, at, "a face property");
        continue;
      }
      const std::size_t n = reader.read_list_length(prop);
      if (static_cast<int>(i) != list) {
        for (std::size_t j = 0; j < n; ++j) reader.read(prop.value_type, at, "a list entry");
        continue;
      }
      corners.clear();
      for (std::size_t j = 0; j < n; ++j) {
        const double v = reader.read(prop.value_type, at, "a vertex index");
        if (j == 0) face_at = at;
        // Range-check before converting: an ASCII "1e300" is integral but not an int.
        if (!(v >= 0 && v <= static_cast<double>(std::numeric_limits<Index>::max())))
          cursor.fail_at(at, fmt::format("face {} has vertex index {}", f, v));
        corners.push_back(static_cast<Index>(v));
      }
    }
    add_polygon(cursor, face_at, corners, options, mesh);
  }
}

/// Any other element (edges, materials, ...): read and discarded, unless it holds vertex index
/// lists: those describe surface pieces (triangle strips, polygons under another name) that
/// would vanish.
void skip_element(Cursor& cursor, ValueReader& reader, const Element& e, std::size_t count) {
  for (const Property& prop : e.properties)
    if (prop.is_list && is_index_list_name(prop.name))
      cursor.fail_at(e.header_offset,
                     fmt::format("element '{}' has a '{}' list{}; plmap reads surface pieces from the 'face' element only",
                                 e.name.substr(0, 40), prop.name, e.name == "tristrips" ? " (triangle strips)" : ""));
  for (std::size_t r = 0; r < count; ++r)
    for (const Property& prop : e.properties) {
      std::size_t at = 0;
      const std::size_t n = prop.is_list ? reader.read_list_length(prop) : 1;
      for (std::size_t j = 0; j < n; ++j) reader.read(prop.value_type, at, "a property value");
    }
}

/// Records after the announced ones would otherwise be ignored: a count in the header is wrong.
void refuse_trailing_data(Cursor& cursor, const Header& header) {
  const std::string_view last = header.elements.empty() ? std::string_view("") : header.elements.back().name;
  if (header.layout == Layout::ascii) {
    if (const std::string_view token = cursor.read_token(); !token.empty())
      cursor.fail_at(token, fmt::format("unexpected data '{}' after the records the header announces "
                                        "(the last element is '{}': is a count wrong?)",
                                        token.substr(0, 40), last.substr(0, 40)));
  } else if (!cursor.at_end()) {
    cursor.fail(fmt::format("{} bytes follow the records the header announces (the last element "
                            "is '{}': is a count wrong?)",
                            cursor.remaining(), last.substr(0, 40)));
  }
}

}  // namespace

RawMesh<2> parse_ply(Cursor& cursor, const SurfaceReadOptions& options) {
  std::string_view line;
  if (!cursor.read_line(line) || line != "ply") cursor.fail_at(0, "not a PLY file: the first line must be 'ply'");
  const Header header = read_header(cursor);
  if (header.layout != Layout::ascii) cursor.use_byte_locations();

  RawMesh<2> mesh;
  ValueReader reader(cursor, header.layout);
  bool seen_vertices = false;
  bool seen_faces = false;
  for (const Element& e : header.elements) {
    const std::size_t count = checked_count(cursor, e.header_offset, static_cast<std::int64_t>(e.count),
                                            min_record_bytes(e, header.layout), e.name);
    if (e.properties.empty()) continue;  // records without properties take no bytes
    if (e.name == "vertex") {
      if (seen_vertices) cursor.fail_at(e.header_offset, "a second 'vertex' element");
      seen_vertices = true;
      read_vertices(cursor, reader, e, count, mesh);
    } else if (e.name == "face") {
      if (seen_faces) cursor.fail_at(e.header_offset, "a second 'face' element");
      seen_faces = true;
      read_faces(cursor, reader, e, count, options, mesh);
    } else {
      skip_element(cursor, reader, e, count);
    }
  }
  if (!seen_vertices) cursor.fail_at(0, "the header declares no 'vertex' element");
  refuse_trailing_data(cursor, header);
  check_elements(cursor, mesh, VertexNumbering::zero_based);
  return mesh;
}

}  // namespace plmap::surface_io_detail
