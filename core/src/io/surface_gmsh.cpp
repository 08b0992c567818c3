// Gmsh MSH reader: versions 2.2 and 4.1, ASCII and binary. Hand-written: libgmsh-dev would
// bring the whole mesher with process-global state into plmap_core, and its errors are not
// located the way plmap's are. Triangles (element type 2) make a triangle surface, lines
// (type 1) make a curve; elements of other dimensions are skipped, elements of the same dimension
// that plmap cannot read refuse the file (see skip_other_type). Only nodes used by the kept
// elements become vertices, in the order of the $Nodes section.
#include "surface_parse_support.hpp"

#include <unordered_map>

namespace plmap::surface_io_detail {

namespace {

/// What plmap knows about one of Gmsh's element types 1..31: its node count (needed to skip such
/// elements in binary files, where there are no line breaks to skip by), its dimension (which
/// decides whether skipping it can change the surface or curve being read) and a description
/// for messages.
struct ElementTypeInfo {
  int nodes = 0;  // 0: a type plmap does not know
  int dimension = 0;
  std::string_view description;
};

ElementTypeInfo element_type_info(std::int64_t type) {
  static constexpr ElementTypeInfo table[] = {
      {},
      {2, 1, "2-node line"},
      {3, 2, "3-node triangle"},
      {4, 2, "4-node quadrangle"},
      {4, 3, "4-node tetrahedron"},
      {8, 3, "8-node hexahedron"},
      {6, 3, "6-node prism"},
      {5, 3, "5-node pyramid"},
      {3, 1, "3-node second-order line"},
      {6, 2, "6-node second-order triangle"},
      {9, 2, "9-node second-order quadrangle"},
      {10, 3, "10-node second-order tetrahedron"},
      {27, 3, "27-node second-order hexahedron"},
      {18, 3, "18-node second-order prism"},
      {14, 3, "14-node second-order pyramid"},
      {1, 0, "point"},
      {8, 2, "8-node second-order quadrangle"},
      {20, 3, "20-node second-order hexahedron"},
      {15, 3, "15-node second-order prism"},
      {13, 3, "13-node second-order pyramid"},
      {9, 2, "9-node third-order triangle"},
      {10, 2, "10-node third-order triangle"},
      {12, 2, "12-node fourth-order triangle"},
      {15, 2, "15-node fourth-order triangle"},
      {15, 2, "15-node fifth-order triangle"},
      {21, 2, "21-node fifth-order triangle"},
      {4, 1, "4-node third-order line"},
      {5, 1, "5-node fourth-order line"},
      {6, 1, "6-node fifth-order line"},
      {20, 3, "20-node third-order tetrahedron"},
      {35, 3, "35-node fourth-order tetrahedron"},
      {56, 3, "56-node fifth-order tetrahedron"},
  };
  if (type < 1 || type >= static_cast<std::int64_t>(std::size(table))) return {};
  return table[type];
}

struct Node {
  Eigen::Vector3d position;
  std::size_t offset;  // where it was defined, for messages
};

template <int d>
struct RawElement {
  std::array<std::uint64_t, d + 1> node_tags;
  std::size_t offset;
};

template <int d>
class GmshParser {
 public:
  GmshParser(Cursor& cursor) : cursor_(cursor) {}

  RawMesh<d> parse() {
    read_format();
    bool have_nodes = false;
    std::string_view line;
    while (cursor_.read_content_line(line, '\0')) {
      const std::string_view section = Tokens(line).next();
      if (section == "$Nodes") {
        if (have_nodes) cursor_.fail_at(section, "a second $Nodes section");
        have_nodes = true;
        if (major_ == 2) read_nodes_v2(); else read_nodes_v4();
        expect_end("$EndNodes");
      } else if (section == "$Elements") {
        if (major_ == 2) read_elements_v2(); else read_elements_v4();
        expect_end("$EndElements");
      } else if (section.starts_with("$") && !section.starts_with("$End")) {
        skip_section(section);
      } else {
        cursor_.fail_at(section, fmt::format("expected a section such as $Nodes, found '{}'",
                                             section.substr(0, 40)));
      }
    }
    if (!have_nodes) cursor_.fail("the file has no $Nodes section");
    return assemble();
  }

 private:
  static constexpr int wanted_type = d == 1 ? 1 : 2;

  void read_format() {
    std::string_view line;
    if (!cursor_.read_content_line(line, '\0') || Tokens(line).next() != "$MeshFormat")
      cursor_.fail_at(0, "not a Gmsh file: it must start with $MeshFormat");
    if (!cursor_.read_line(line)) cursor_.fail("file ends inside $MeshFormat");
    Tokens t(line);
    const std::string_view version = t.next();
    const std::int64_t file_type = read_integer(cursor_, t.next(), "the file type (0 or 1)");
    const std::int64_t data_size = read_integer(cursor_, t.next(), "the data size");
    if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2") major_ = 2;
    else if (version == "4.1") major_ = 4;
    else if (version == "4" || version == "4.0")
      cursor_.fail_at(version, "MSH 4.0 is not supported; save as MSH 4.1 or 2.2");
    else cursor_.fail_at(version, fmt::format("unsupported MSH version '{}'", version.substr(0, 40)));
    if (file_type != 0 && file_type != 1) cursor_.fail_at(line, "file type must be 0 (ASCII) or 1 (binary)");
    binary_ = file_type == 1;
    if (binary_) {
      if (data_size != 8) cursor_.fail_at(line, "binary MSH files must have data size 8");
      // The integer 1 written in the writer's byte order tells the order.
      const std::size_t at = cursor_.position();
      const auto one = cursor_.read_binary<std::int32_t>(false, "the byte-order mark");
      if (one == 1) big_endian_ = false;
      else if (one == 0x01000000) big_endian_ = true;
      else cursor_.fail_at(at, "bad byte-order mark in binary $MeshFormat");
      cursor_.read_line(line);  // the rest of the mark's line
      cursor_.use_byte_locations();
    }
    expect_end("$EndMeshFormat");
  }

  void expect_end(std::string_view name) {
    std::string_view line;
    if (!cursor_.read_content_line(line, '\0'))
      cursor_.fail(fmt::format("file ends where {} was expected", name));
    const std::string_view token = Tokens(line).next();
    if (token != name)
      cursor_.fail_at(token, fmt::format("expected {}, found '{}'", name, token.substr(0, 40)));
  }

  void skip_section(std::string_view section) {
    const std::string end = "$End" + std::string(section.substr(1));
    const std::size_t at = cursor_.offset_of(section);
    std::string_view line;
    while (cursor_.read_line(line))
      if (Tokens(line).next() == end) return;
    cursor_.fail_at(at, fmt::format("section {} has no {}", section.substr(0, 40), end));
  }

  std::int64_t integer_token(std::string_view what) {
    return read_integer(cursor_, cursor_.read_token(), what);
  }

  void add_node(std::uint64_t tag, const Eigen::Vector3d& p, std::size_t at) {
    for (int k = 0; k < 3; ++k) check_finite(cursor_, at, p(k), fmt::format("a coordinate of node {}", tag));
    const auto [it, inserted] = node_index_.try_emplace(tag, nodes_.size());
    if (!inserted) cursor_.fail_at(at, fmt::format("node tag {} appears twice", tag));
    nodes_.push_back({p, at});
  }

  void read_nodes_v2() {
    const std::size_t count_at = cursor_.position();
    const std::int64_t count = integer_token("the node count");
    const std::size_t n = checked_count(cursor_, count_at, count, binary_ ? 28 : 2, "node");
    if (binary_) {
      std::string_view rest;
      cursor_.read_line(rest);  // binary records start on the line after the count
    }
    nodes_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (binary_) {
        const std::size_t at = cursor_.position();
        const auto tag = cursor_.read_binary<std::int32_t>(big_endian_, "a node tag");
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p(k) = cursor_.read_binary<double>(big_endian_, "a node coordinate");
        if (tag < 0) cursor_.fail_at(at, fmt::format("negative node tag {}", tag));
        add_node(static_cast<std::uint64_t>(tag), p, at);
      } else {
        std::string_view line;
        if (!cursor_.read_content_line(line, '\0'))
          cursor_.fail(fmt::format("file ends after {} of {} nodes", i, n));
        Tokens t(line);
        const std::string_view tag_token = t.next();
        const std::int64_t tag = read_integer(cursor_, tag_token, "a node tag");
        if (tag < 0) cursor_.fail_at(line, fmt::format("negative node tag {}", tag));
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p(k) = read_coordinate(cursor_, t.next(), "a node coordinate");
        add_node(static_cast<std::uint64_t>(tag), p, cursor_.offset_of(line));
      }
    }
  }

  void keep_element(std::span<const std::uint64_t> tags, std::size_t at) {
    // Checked here, by tag: the vertex numbers assigned later mean nothing to the file's reader.
    for (std::size_t k = 0; k < tags.size(); ++k)
      for (std::size_t j = 0; j < k; ++j)
        if (tags[j] == tags[k]) cursor_.fail_at(at, fmt::format("element uses node {} twice", tags[k]));
    RawElement<d> e;
    std::copy(tags.begin(), tags.end(), e.node_tags.begin());
    elements_.push_back(e);
    elements_.back().offset = at;
  }

  void read_elements_v2() {
    const std::size_t count_at = cursor_.position();
    const std::int64_t count = integer_token("the element count");
    const std::size_t m = checked_count(cursor_, count_at, count, binary_ ? 8 : 2, "element");
    std::array<std::uint64_t, d + 1> tags{};
    if (!binary_) {
      std::string_view line;
      for (std::size_t i = 0; i < m; ++i) {
        if (!cursor_.read_content_line(line, '\0'))
          cursor_.fail(fmt::format("file ends after {} of {} elements", i, m));
        Tokens t(line);
        read_integer(cursor_, t.next(), "an element tag");
        const std::int64_t type = read_integer(cursor_, t.next(), "an element type");
        const std::int64_t tag_count = read_integer(cursor_, t.next(), "the number of tags");
        if (tag_count < 0 || static_cast<std::uint64_t>(tag_count) > line.size())
          cursor_.fail_at(line, fmt::format("bad number of element tags {}", tag_count));
        if (type != wanted_type) {
          skip_other_type(type, cursor_.offset_of(line));
          continue;
        }
        for (std::int64_t k = 0; k < tag_count; ++k) read_integer(cursor_, t.next(), "an element tag");
        for (int k = 0; k <= d; ++k) {
          const std::int64_t node = read_integer(cursor_, t.next(), "a node tag");
          if (node < 0) cursor_.fail_at(line, fmt::format("negative node tag {}", node));
          tags[k] = static_cast<std::uint64_t>(node);
        }
        if (!t.empty()) cursor_.fail_at(line, fmt::format("element has more than {} nodes", d + 1));
        keep_element(tags, cursor_.offset_of(line));
      }
      return;
    }
    std::string_view rest;
    cursor_.read_line(rest);
    std::size_t read = 0;
    while (read < m) {
      const std::size_t at = cursor_.position();
      const auto type = cursor_.read_binary<std::int32_t>(big_endian_, "an element type");
      const auto following = cursor_.read_binary<std::int32_t>(big_endian_, "an element block size");
      const auto tag_count = cursor_.read_binary<std::int32_t>(big_endian_, "the number of tags");
      const int nodes = type == wanted_type ? d + 1 : skip_other_type(type, at);
      if (following < 1 || static_cast<std::size_t>(following) > m - read)
        cursor_.fail_at(at, fmt::format("bad element block size {}", following));
      if (tag_count < 0) cursor_.fail_at(at, fmt::format("bad number of tags {}", tag_count));
      const std::size_t ints_each = 1 + static_cast<std::size_t>(tag_count) + nodes;
      checked_count(cursor_, at, following, 4 * ints_each, "element");
      for (std::int32_t i = 0; i < following; ++i) {
        const std::size_t element_at = cursor_.position();
        if (type != wanted_type) {
          cursor_.skip(4 * ints_each, "an element");
          continue;
        }
        cursor_.skip(4 * (1 + static_cast<std::size_t>(tag_count)), "an element's tags");
        for (int k = 0; k <= d; ++k) {
          const auto node = cursor_.read_binary<std::int32_t>(big_endian_, "a node tag");
          if (node < 0) cursor_.fail_at(element_at, fmt::format("negative node tag {}", node));
          tags[k] = static_cast<std::uint64_t>(node);
        }
        keep_element(tags, element_at);
      }
      read += static_cast<std::size_t>(following);
    }
  }

  /// An unsigned size: a size_t in binary files, a token in ASCII ones.
  std::uint64_t size_value(std::string_view what) {
    if (binary_) return cursor_.read_binary<std::uint64_t>(big_endian_, what);
    const std::string_view token = cursor_.read_token();
    const std::int64_t v = read_integer(cursor_, token, what);
    if (v < 0) cursor_.fail_at(token, fmt::format("{} is negative", what));
    return static_cast<std::uint64_t>(v);
  }
  std::int64_t int_value(std::string_view what) {
    if (binary_) return cursor_.read_binary<std::int32_t>(big_endian_, what);
    return integer_token(what);
  }
  /// A count of `noun`s (e.g. "node block"), read as `what` and bounded by the bytes left.
  std::size_t count_value(std::string_view what, std::string_view noun, std::size_t min_bytes_each) {
    const std::size_t at = cursor_.position();
    const std::uint64_t v = size_value(what);
    if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      cursor_.fail_at(at, fmt::format("{} {} is too large", what, v));
    return checked_count(cursor_, at, static_cast<std::int64_t>(v), min_bytes_each, noun);
  }

  void read_nodes_v4() {
    const std::size_t blocks = count_value("the node block count", "node block", binary_ ? 20 : 2);
    const std::size_t total = count_value("the node count", "node", binary_ ? 32 : 2);
    size_value("the smallest node tag");
    size_value("the largest node tag");
    nodes_.reserve(total);
    std::size_t seen = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = int_value("an entity dimension");
      int_value("an entity tag");
      const std::int64_t parametric = int_value("the parametric flag");
      const std::size_t n = count_value("the block's node count", "node", binary_ ? 32 : 2);
      if (dim < 0 || dim > 3) cursor_.fail(fmt::format("bad entity dimension {}", dim));
      if (parametric != 0 && parametric != 1) cursor_.fail("the parametric flag must be 0 or 1");
      if (n > total - seen) cursor_.fail(fmt::format("node blocks hold more than the {} nodes announced", total));
      std::vector<std::pair<std::uint64_t, std::size_t>> tags(n);
      for (auto& [tag, at] : tags) {
        at = cursor_.position();
        tag = size_value("a node tag");
      }
      const int values = 3 + (parametric == 1 ? static_cast<int>(dim) : 0);
      for (const auto& [tag, tag_at] : tags) {
        const std::size_t at = binary_ ? cursor_.position() : tag_at;
        Eigen::Vector3d p;
        for (int k = 0; k < values; ++k) {
          double value;
          if (binary_) value = cursor_.read_binary<double>(big_endian_, "a node coordinate");
          else value = read_coordinate(cursor_, cursor_.read_token(), "a node coordinate");
          if (k < 3) p(k) = value;
        }
        add_node(tag, p, at);
      }
      seen += n;
    }
    if (seen != total) cursor_.fail(fmt::format("node blocks hold {} nodes, but {} were announced", seen, total));
  }

  void read_elements_v4() {
    const std::size_t blocks = count_value("the element block count", "element block", binary_ ? 20 : 2);
    const std::size_t total = count_value("the element count", "element", binary_ ? 16 : 2);
    size_value("the smallest element tag");
    size_value("the largest element tag");
    std::array<std::uint64_t, d + 1> tags{};
    std::size_t seen = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      int_value("an entity dimension");
      int_value("an entity tag");
      const std::size_t type_at = cursor_.position();
      const std::int64_t type = int_value("an element type");
      const std::size_t n = count_value("the block's element count", "element", binary_ ? 16 : 2);
      if (n > total - seen) cursor_.fail(fmt::format("element blocks hold more than the {} elements announced", total));
      seen += n;
      // An empty block drops nothing, so only a block with elements is judged.
      const int nodes = type == wanted_type || n == 0 ? element_type_info(type).nodes
                                                       : skip_other_type(type, type_at);
      if (binary_) {
        if (nodes == 0) cursor_.fail_at(type_at, fmt::format("unknown Gmsh element type {}", type));
        const std::size_t bytes_each = 8 * (1 + static_cast<std::size_t>(nodes));
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t at = cursor_.position();
          if (type != wanted_type) {
            cursor_.skip(bytes_each, "an element");
            continue;
          }
          size_value("an element tag");
          for (int k = 0; k <= d; ++k) tags[k] = size_value("a node tag");
          keep_element(tags, at);
        }
        continue;
      }
      std::string_view line;
      cursor_.read_line(line);  // the rest of the block header's line: an element there would be lost
      if (!Tokens(line).empty())
        cursor_.fail_at(line, "unexpected text after an element block header (elements start on "
                              "the next line)");
      for (std::size_t i = 0; i < n; ++i) {
        if (!cursor_.read_content_line(line, '\0'))
          cursor_.fail(fmt::format("file ends inside an element block"));
        if (type != wanted_type) continue;  // judged above, from the block header
        Tokens t(line);
        read_integer(cursor_, t.next(), "an element tag");
        for (int k = 0; k <= d; ++k) {
          const std::string_view token = t.next();
          const std::int64_t node = read_integer(cursor_, token, "a node tag");
          if (node < 0) cursor_.fail_at(token, fmt::format("negative node tag {}", node));
          tags[k] = static_cast<std::uint64_t>(node);
        }
        if (!t.empty()) cursor_.fail_at(line, fmt::format("element has more than {} nodes", d + 1));
        keep_element(tags, cursor_.offset_of(line));
      }
    }
    if (seen != total) cursor_.fail(fmt::format("element blocks hold {} elements, but {} were announced", seen, total));
  }

  /// Decides about elements of a type other than the one being read, at `at` (the element or
  /// its block header); returns the type's node count. Elements of another dimension (points,
  /// lines in a surface file, volumes, triangles in a curve file) are skipped on purpose: they
  /// do not belong to the surface or curve. An element of the same dimension that plmap cannot
  /// read (a quadrangle, a higher-order triangle or line) is part of it, and dropping it would
  /// leave a hole, so the file is refused; so is a type plmap does not know.
  int skip_other_type(std::int64_t type, std::size_t at) {
    const ElementTypeInfo info = element_type_info(type);
    if (info.nodes == 0)
      cursor_.fail_at(at, fmt::format("unknown Gmsh element type {} (plmap knows types 1 to 31)", type));
    if (info.dimension == d)
      cursor_.fail_at(at, fmt::format("Gmsh element type {} ({}) cannot be read: plmap reads {} "
                                      "from {} (type {}) only; export a first-order {} mesh",
                                      type, info.description, d == 1 ? "curves" : "triangle surfaces",
                                      d == 1 ? "2-node lines" : "3-node triangles", wanted_type,
                                      d == 1 ? "line" : "triangle"));
    return info.nodes;
  }

  RawMesh<d> assemble() {
    if (elements_.empty())
      throw ParseError(cursor_.file(), "",
                       fmt::format("the file has no {} elements (Gmsh type {})",
                                   d == 1 ? "line" : "triangle", wanted_type));
    // Only nodes used by the kept elements become vertices, numbered in $Nodes order.
    std::vector<Index> vertex_of_node(nodes_.size(), invalid_index);
    std::vector<std::array<std::size_t, d + 1>> element_nodes(elements_.size());
    for (std::size_t t = 0; t < elements_.size(); ++t)
      for (int k = 0; k <= d; ++k) {
        const auto it = node_index_.find(elements_[t].node_tags[k]);
        if (it == node_index_.end())
          cursor_.fail_at(elements_[t].offset,
                          fmt::format("element refers to node {}, which is not in $Nodes",
                                      elements_[t].node_tags[k]));
        element_nodes[t][k] = it->second;
        vertex_of_node[it->second] = 0;  // mark as used
      }
    RawMesh<d> mesh;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      if (vertex_of_node[i] == invalid_index) continue;
      vertex_of_node[i] = static_cast<Index>(mesh.vertices.size());
      const Eigen::Vector3d& p = nodes_[i].position;
      if constexpr (d == 1) {
        // Curves live in the plane: a node off z = 0 means the file is not a plane curve, and
        // dropping z silently would change its geometry.
        if (p(2) != 0.0)
          cursor_.fail_at(nodes_[i].offset,
                          fmt::format("curve node has z = {}; plane curves need z = 0", p(2)));
        mesh.vertices.push_back(WorldPoint<1>(p(0), p(1)));
      } else {
        mesh.vertices.push_back(p);
      }
    }
    mesh.elements.reserve(elements_.size());
    for (std::size_t t = 0; t < elements_.size(); ++t) {
      ElementCorners<d> corners;
      for (int k = 0; k <= d; ++k) corners[k] = vertex_of_node[element_nodes[t][k]];
      mesh.elements.push_back(corners);
      mesh.element_offset.push_back(elements_[t].offset);
    }
    check_elements(cursor_, mesh, VertexNumbering::internal);
    return mesh;
  }

  Cursor& cursor_;
  int major_ = 0;
  bool binary_ = false;
  bool big_endian_ = false;
  std::vector<Node> nodes_;
  std::unordered_map<std::uint64_t, std::size_t> node_index_;
  std::vector<RawElement<d>> elements_;
};

}  // namespace

template <int d>
RawMesh<d> parse_gmsh(Cursor& cursor, const SurfaceReadOptions&) {
  return GmshParser<d>(cursor).parse();
}

template RawMesh<1> parse_gmsh<1>(Cursor&, const SurfaceReadOptions&);
template RawMesh<2> parse_gmsh<2>(Cursor&, const SurfaceReadOptions&);

}  // namespace plmap::surface_io_detail
