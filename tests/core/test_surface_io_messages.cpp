// The readers' messages say what is wrong in the file's own terms (issue 12, defect 9): a
// duplicate PLY property is called that (not a degenerate element), counts are not "count
// count", vertex numbers are the file's, and no message repeats a word.
#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/io/surface_reader.hpp>

#include <gtest/gtest.h>

#include <regex>
#include <string>

using namespace plmap;

namespace {

/// The message of the ParseError that parsing `content` raises ("" and a test failure if none).
template <int d = 2>
std::string parse_error_of(const std::string& content, SurfaceFormat format, const std::string& file) {
  try {
    parse_surface<d>(content, format, file);
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), file) << e.what();
    return e.what();
  } catch (const Error& e) {
    ADD_FAILURE() << "not a ParseError: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << file << " was read";
  return "";
}

/// A word written twice in a row ("count count"), case-insensitive.
bool has_doubled_word(const std::string& message) {
  static const std::regex doubled(R"(\b([A-Za-z]+) \1\b)", std::regex::icase);
  return std::regex_search(message, doubled);
}

}  // namespace

TEST(SurfaceIoMessages, DuplicatePlyPropertyIsNamedWithItsLine) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0\n1 1 0 0\n0 0 1 0\n3 0 1 2\n";
  EXPECT_EQ(parse_error_of(ply, SurfaceFormat::ply, "dup.ply"),
            "dup.ply:line 5: duplicate property 'x' in element 'vertex'");
}

TEST(SurfaceIoMessages, GmshCountsAreNotCountCount) {
  // MSH 4.1 node and element counts larger than the file can hold.
  const std::string nodes = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 99999 1 99999\n";
  const std::string m1 = parse_error_of(nodes, SurfaceFormat::gmsh, "n.msh");
  EXPECT_NE(m1.find("node count 99999 cannot fit"), std::string::npos) << m1;
  EXPECT_FALSE(has_doubled_word(m1)) << m1;
  const std::string blocks = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n99999 1 1 1\n";
  const std::string m2 = parse_error_of(blocks, SurfaceFormat::gmsh, "b.msh");
  EXPECT_NE(m2.find("node block count 99999"), std::string::npos) << m2;
  EXPECT_FALSE(has_doubled_word(m2)) << m2;
  const std::string block_nodes =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 99999\n1\n0 0 0\n$EndNodes\n";
  const std::string m3 = parse_error_of(block_nodes, SurfaceFormat::gmsh, "bn.msh");
  EXPECT_FALSE(has_doubled_word(m3)) << m3;
  const std::string elements =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0\n$EndNodes\n"
      "$Elements\n1 99999 1 99999\n";
  const std::string m4 = parse_error_of(elements, SurfaceFormat::gmsh, "e.msh");
  EXPECT_NE(m4.find("element count 99999"), std::string::npos) << m4;
  EXPECT_FALSE(has_doubled_word(m4)) << m4;
}

TEST(SurfaceIoMessages, CurveCountsUseTheSingularNoun) {
  const std::string m = parse_error_of<1>("plmap-curve 1\nvertices 99999\n0 0\n", SurfaceFormat::curve, "c.curve");
  EXPECT_NE(m.find("vertex count 99999"), std::string::npos) << m;
  const std::string s = parse_error_of<1>("plmap-curve 1\nvertices 2\n0 0\n1 0\nsegments 99999\n0 1\n",
                                          SurfaceFormat::curve, "s.curve");
  EXPECT_NE(s.find("segment count 99999"), std::string::npos) << s;
}

TEST(SurfaceIoMessages, VertexNumbersAreTheFilesOwn) {
  // OBJ counts from 1: a forward reference past the end names the index the file uses.
  EXPECT_EQ(parse_error_of("v 0 0 0\nf 1 2 4\nv 1 0 0\nv 0 1 0\n", SurfaceFormat::obj, "g.obj"),
            "g.obj:line 2: element refers to vertex 4, but the file has 3 vertices (numbered from 1)");
  EXPECT_EQ(parse_error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 2 2\n", SurfaceFormat::off, "r.off"),
            "r.off:line 6: element uses vertex 2 twice");
  // Gmsh names the node tag, not a vertex number of plmap's.
  EXPECT_EQ(parse_error_of("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n10 0 0 0\n20 1 0 0\n30 0 1 0\n"
                           "$EndNodes\n$Elements\n1\n1 2 0 10 30 30\n$EndElements\n",
                           SurfaceFormat::gmsh, "t.msh"),
            "t.msh:line 12: element uses node 30 twice");
}

TEST(SurfaceIoMessages, NoMessageRepeatsAWord) {
  // One malformed file per count and per kind of message the readers build from parts.
  const struct {
    const char* name;
    SurfaceFormat format;
    int dimension;
    std::string content;
  } cases[] = {
      {"a.off", SurfaceFormat::off, 2, "OFF\n99999 1 0\n"},
      {"b.off", SurfaceFormat::off, 2, "OFF\n3 99999 0\n0 0 0\n1 0 0\n0 1 0\n"},
      {"c.ply", SurfaceFormat::ply, 2,
       "ply\nformat binary_little_endian 1.0\nelement vertex 99999\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n"},
      {"d.ply", SurfaceFormat::ply, 2,
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n"},
      {"e.stl", SurfaceFormat::stl, 2, std::string(80, ' ') + std::string("\x9f\x86\x01\0", 4)},
      {"f.msh", SurfaceFormat::gmsh, 2, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n99999\n"},
      {"g.msh", SurfaceFormat::gmsh, 2,
       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n99999\n"},
      {"h.msh", SurfaceFormat::gmsh, 2,
       "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0\n$EndNodes\n"
       "$Elements\n1 1 1 1\n2 1 2 99999\n"},
      {"i.curve", SurfaceFormat::curve, 1, "plmap-curve 1\nvertices 1\n0 0\nsegments 9999\n"},
  };
  for (const auto& c : cases) {
    const std::string m = c.dimension == 1 ? parse_error_of<1>(c.content, c.format, c.name)
                                           : parse_error_of<2>(c.content, c.format, c.name);
    EXPECT_FALSE(has_doubled_word(m)) << m;
    EXPECT_TRUE(m.starts_with(std::string(c.name) + ":")) << m;
  }
}

namespace {

std::string invalid_surface_error_of(const std::string& content, SurfaceFormat format, const std::string& file) {
  try {
    parse_surface<2>(content, format, file);
  } catch (const InvalidSurfaceError& e) {
    return e.what();
  }
  ADD_FAILURE() << file << ": no InvalidSurfaceError";
  return "";
}

}  // namespace

TEST(SurfaceIoMessages, SurfaceErrorsNameLinesNotInternalElementNumbers) {
  // Surface numbers elements after polygons are split; the message uses the file's lines.
  const std::string square = "OFF\n5 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n";  // faces from line 8
  // The polygon 0 1 2 1 splits into (0 1 2) and (0 2 1).
  EXPECT_EQ(invalid_surface_error_of(square + "4 0 1 2 1\n3 0 2 3\n3 1 4 2\n", SurfaceFormat::off, "d.off"),
            "d.off:line 8: two pieces of the polygon at line 8 have the same three vertices");
  EXPECT_EQ(invalid_surface_error_of(square + "4 0 1 2 3\n3 1 2 3\n3 2 1 0\n", SurfaceFormat::off, "e.off"),
            "e.off:line 8: the elements at line 8 and line 10 have the same three vertices");
  // A polygon whose corners all lie on one line: no triangulation avoids a degenerate triangle.
  // (One straight corner is no such case: the polygon is cut at it, test_surface_io_polygons.cpp.)
  const std::string line_of_four = "OFF\n6 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n3 0 0\n";  // faces from line 9
  const std::string degenerate = invalid_surface_error_of(line_of_four + "4 0 1 4 5\n3 0 2 3\n3 1 2 4\n",
                                                          SurfaceFormat::off, "g.off");
  EXPECT_TRUE(degenerate.starts_with("g.off:line 9: a triangle of the polygon here is degenerate")) << degenerate;
  const std::string single = invalid_surface_error_of(square + "3 0 1 2\n3 0 1 4\n3 0 2 3\n",
                                                      SurfaceFormat::off, "s.off");
  EXPECT_TRUE(single.starts_with("s.off:line 9: this element is degenerate")) << single;
}
