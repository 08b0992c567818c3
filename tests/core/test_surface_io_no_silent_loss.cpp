// No reader drops surface data without saying so (issue 12, defect 7): data after the announced
// counts, elements a reader cannot read, statements it does not know. Each case is either read
// completely or refused with a ParseError naming the file and the line or byte. What is skipped
// on purpose (points and lines in a surface file, colours, ...) is pinned down here as well, as
// documented in docs/surface-formats.md.
#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/io/surface_reader.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace plmap;

namespace {

/// Parses `content` and expects a ParseError for `file` at `location` whose message contains
/// `words`.
template <int d = 2>
void expect_refused(const std::string& content, SurfaceFormat format, const std::string& file,
                    const std::string& location, const std::string& words) {
  try {
    const Surface<d> s = parse_surface<d>(content, format, file);
    ADD_FAILURE() << file << ": read " << s.element_count() << " elements instead of refusing";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), file) << e.what();
    EXPECT_EQ(e.location(), location) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

// ---- binary builders (little endian, as written on every machine plmap runs on) ----

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// A binary STL holding `facets` facets (two triangles of a square, repeated) whose header
/// announces `announced`, followed by `stray` extra bytes.
std::string binary_stl(std::uint32_t announced, int facets, int stray = 0,
                       const std::string& header_start = "binary") {
  std::string out = header_start;
  out.resize(80, ' ');
  put(out, announced);
  const float corners[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (int f = 0; f < facets; ++f) {
    for (int k = 0; k < 3; ++k) put(out, 0.0f);  // normal
    for (float c : corners[f % 2]) put(out, c + static_cast<float>(f / 2));
    put(out, std::uint16_t{0});
  }
  out.append(static_cast<std::size_t>(stray), '\x01');
  return out;
}

const std::string off_header_square = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

const std::string ply_square_header =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
const std::string ply_square_data = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

const std::string msh_v2_head =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
    "5 0.5 0 0\n6 0.5 0.5 0\n$EndNodes\n";  // lines 1-12, elements from line 15 on

}  // namespace

// ---- OFF ----

TEST(SurfaceIoNoSilentLoss, OffRefusesLinesAfterTheAnnouncedFaces) {
  // Two faces announced as one: the second one used to vanish.
  expect_refused("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", SurfaceFormat::off,
                 "short.off", "line 8", "after the 1 faces");
  expect_refused("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n# fine\n\ngarbage\n",
                 SurfaceFormat::off, "tail.off", "line 10", "unexpected line");
  // Comments and blank lines after the last face are no data.
  EXPECT_EQ(parse_surface<2>(off_header_square + "3 0 1 2\n3 0 2 3\n\n# end\n", SurfaceFormat::off, "ok.off")
                .element_count(),
            2);
}

TEST(SurfaceIoNoSilentLoss, OffFaceColoursAreBoundedAndNumeric) {
  // A colour index, RGB and RGBA are fine.
  for (const std::string colour : {"", " 7", " 255 0 0", " 0.5 0.5 0.5 1"})
    EXPECT_EQ(parse_surface<2>(off_header_square + "3 0 1 2" + colour + "\n3 0 2 3\n", SurfaceFormat::off,
                               "c.off")
                  .element_count(),
              2)
        << colour;
  // Two faces on one line: the second is no colour. (A second triangle would pass for an RGBA
  // colour; the count check above catches that file, as its last face is missing.)
  expect_refused(off_header_square + "3 0 1 2 4 0 1 2 3\n3 0 2 3\n", SurfaceFormat::off, "two.off",
                 "line 7", "5 numbers after its 3 vertex indices");
  // A face with a wrong vertex count leaves words no colour has.
  expect_refused(off_header_square + "3 0 1 2 x\n3 0 2 3\n", SurfaceFormat::off, "word.off", "line 7",
                 "face colour component");
}

// ---- OBJ ----

TEST(SurfaceIoNoSilentLoss, ObjRefusesStatementsThatMayCarryGeometry) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  expect_refused(square + "f 1 2 3\nF 1 3 4\n", SurfaceFormat::obj, "upper.obj", "line 6",
                 "unknown OBJ statement 'F'");
  expect_refused(square + "f 1 2 3\nsurf 0 1 0 1 1 2 3 4\n", SurfaceFormat::obj, "surf.obj", "line 6",
                 "free-form surface");
  expect_refused(square + "call other.obj\nf 1 2 3\n", SurfaceFormat::obj, "call.obj", "line 5", "'call'");
  // Three vertices on one line: the two after the first used to vanish.
  expect_refused("v 0 0 0 1 0 0 1 1 0\n", SurfaceFormat::obj, "many.obj", "line 1", "6 numbers");
}

TEST(SurfaceIoNoSilentLoss, ObjReadsOldFaceStatementsAndSkipsWhatHasNoArea) {
  const std::string file =
      "mtllib a.mtl\no square\ng part\ns off\nusemtl red\n"
      "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 1 1 0 0 0 0 1\nv 0 1 0\nvt 0 0\nvn 0 0 1\nvp 0.5\n"
      "l 1 2 3\np 4\ncstype bspline\ndeg 1\ncurv 0 1 1 2\nparm u 0 0 1 1\nend\n"
      "f 1 2 3\nfo 1 3 4\n";
  const Surface<2> s = parse_surface<2>(file, SurfaceFormat::obj, "mixed.obj");
  EXPECT_EQ(s.element_count(), 2);  // "fo" is the old name of "f", not something to skip
  EXPECT_EQ(s.vertex_count(), 4);
}

// ---- STL ----

TEST(SurfaceIoNoSilentLoss, BinaryStlRefusesFacetsBeyondTheAnnouncedCount) {
  EXPECT_EQ(parse_surface<2>(binary_stl(2, 2), SurfaceFormat::stl, "ok.stl").element_count(), 2);
  // Two facets present, one announced: the second used to vanish.
  expect_refused(binary_stl(1, 2), SurfaceFormat::stl, "short.stl", "byte 134",
                 "facet count is 1, but 50 more bytes follow");
  // The same with a header that starts with "solid", which binary files may do.
  expect_refused(binary_stl(1, 2, 0, "solid exported"), SurfaceFormat::stl, "solid.stl", "byte 134",
                 "facet count is 1");
  // Stray bytes that cannot be a facet.
  expect_refused(binary_stl(2, 2, 3), SurfaceFormat::stl, "stray.stl", "byte 184", "3 stray bytes");
  // More announced than present was already refused.
  expect_refused(binary_stl(3, 2), SurfaceFormat::stl, "long.stl", "byte 80", "cannot fit");
}

TEST(SurfaceIoNoSilentLoss, AsciiStlRefusesAFacetOnTheSolidLine) {
  const std::string facet = "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n";
  expect_refused("solid x facet normal 0 0 1\n" + facet + "endsolid x\n", SurfaceFormat::stl, "a.stl",
                 "line 1", "'facet' on the line");
  EXPECT_EQ(parse_surface<2>("solid x y z\nfacet normal 0 0 1\n" + facet + "endsolid x y z\n",
                             SurfaceFormat::stl, "ok.stl")
                .element_count(),
            1);
}

// ---- PLY ----

TEST(SurfaceIoNoSilentLoss, AsciiPlyRefusesRecordsAfterTheAnnouncedOnes) {
  EXPECT_EQ(parse_surface<2>(ply_square_header + ply_square_data, SurfaceFormat::ply, "ok.ply").element_count(), 2);
  expect_refused(ply_square_header + ply_square_data + "3 1 2 3\n", SurfaceFormat::ply, "extra.ply", "line 16",
                 "unexpected data '3'");
}

TEST(SurfaceIoNoSilentLoss, BinaryPlyRefusesBytesAfterTheAnnouncedRecords) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (float c : xyz) put(ply, c);
  put(ply, std::uint8_t{3});
  for (std::int32_t v : {0, 1, 2}) put(ply, v);
  EXPECT_EQ(parse_surface<2>(ply, SurfaceFormat::ply, "ok.ply").element_count(), 1);
  const std::string data_end = "byte " + std::to_string(ply.size());
  put(ply, std::uint8_t{3});  // a second face the header does not announce
  for (std::int32_t v : {2, 1, 0}) put(ply, v);
  expect_refused(ply, SurfaceFormat::ply, "extra.ply", data_end, "13 bytes follow");
}

TEST(SurfaceIoNoSilentLoss, PlyRefusesVertexIndexListsOutsideTheFaceElement) {
  const std::string strips =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 3 2\n";
  expect_refused(strips, SurfaceFormat::ply, "strips.ply", "line 7", "element 'tristrips' has a 'vertex_indices' list");
  const std::string both =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar int vertex_index\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 3 0 1 2\n";
  expect_refused(both, SurfaceFormat::ply, "both.ply", "line 7", "both 'vertex_indices' and 'vertex_index'");
  // Elements without index lists (edges, materials) carry no surface and are skipped.
  const std::string edges =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nelement edge 1\nproperty int vertex1\n"
      "property int vertex2\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 1\n";
  EXPECT_EQ(parse_surface<2>(edges, SurfaceFormat::ply, "edges.ply").element_count(), 1);
}

// ---- Gmsh ----

TEST(SurfaceIoNoSilentLoss, GmshV2RefusesSurfaceElementsItCannotRead) {
  // A triangle next to a second-order triangle: the second one used to vanish.
  const std::string p2 = msh_v2_head + "$Elements\n2\n1 2 0 1 2 4\n2 9 0 2 3 4 5 6 1\n$EndElements\n";
  expect_refused(p2, SurfaceFormat::gmsh, "p2.msh", "line 16", "Gmsh element type 9 (6-node second-order triangle)");
  const std::string quad = msh_v2_head + "$Elements\n2\n1 2 0 1 2 4\n2 3 0 2 3 4 5\n$EndElements\n";
  expect_refused(quad, SurfaceFormat::gmsh, "quad.msh", "line 16", "type 3 (4-node quadrangle)");
  const std::string unknown = msh_v2_head + "$Elements\n2\n1 2 0 1 2 4\n2 99 0 2 3 4\n$EndElements\n";
  expect_refused(unknown, SurfaceFormat::gmsh, "u.msh", "line 16", "unknown Gmsh element type 99");
  // Points, lines and volumes do not belong to a triangle surface and are skipped on purpose.
  const std::string mixed = msh_v2_head +
                            "$Elements\n5\n1 15 0 1\n2 1 0 1 2\n3 2 0 1 2 3\n4 2 0 1 3 4\n"
                            "5 4 0 1 2 3 6\n$EndElements\n";
  EXPECT_EQ(parse_surface<2>(mixed, SurfaceFormat::gmsh, "mixed.msh").element_count(), 2);
  // A curve refuses second-order lines, and skips triangles.
  const std::string curve = msh_v2_head + "$Elements\n2\n1 1 0 1 2\n2 8 0 2 3 5\n$EndElements\n";
  expect_refused<1>(curve, SurfaceFormat::gmsh, "c.msh", "line 16", "type 8 (3-node second-order line)");
}

TEST(SurfaceIoNoSilentLoss, GmshV4RefusesABlockOfSurfaceElementsItCannotRead) {
  const std::string head =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0 0\n0.5 0.5 0\n$EndNodes\n";  // lines 1-19
  const std::string file = head +
                           "$Elements\n2 8 1 8\n2 1 2 7\n1 1 2 4\n2 2 3 4\n3 1 2 3\n4 1 3 4\n5 1 2 6\n"
                           "6 2 3 6\n7 3 4 6\n2 1 9 1\n8 1 2 3 5 6 4\n$EndElements\n";
  // The block header of the type-9 block is line 30.
  expect_refused(file, SurfaceFormat::gmsh, "p2v4.msh", "line 30", "type 9 (6-node second-order triangle)");
  // An element on the block header's line (the block's count then covers the lines after it).
  expect_refused(head + "$Elements\n1 2 1 3\n2 1 2 2 1 1 2 4\n2 2 3 4\n3 1 2 3\n$EndElements\n",
                 SurfaceFormat::gmsh, "header.msh", "line 22", "after an element block header");
  // The same file with the block as points is read, 7 triangles.
  std::string points = file;
  points.replace(points.find("2 1 9 1\n8 1 2 3 5 6 4\n"), 21, "0 1 15 1\n8 5\n");
  EXPECT_EQ(parse_surface<2>(points, SurfaceFormat::gmsh, "pts.msh").element_count(), 7);
}

namespace {

/// Binary MSH files with six nodes, one 3-node triangle and, if `with_p2`, one 6-node
/// triangle (type 9) after it; `p2_at` receives the offset of the type-9 block's header (v2) or
/// its element type (v4).
std::string binary_msh_v2(bool with_p2, std::size_t& p2_at) {
  std::string out = "$MeshFormat\n2.2 1 8\n";
  put(out, std::int32_t{1});
  out += "\n$EndMeshFormat\n$Nodes\n6\n";
  const double xyz[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}};
  for (int i = 0; i < 6; ++i) {
    put(out, std::int32_t{i + 1});
    for (double c : xyz[i]) put(out, c);
  }
  out += with_p2 ? "\n$EndNodes\n$Elements\n2\n" : "\n$EndNodes\n$Elements\n1\n";
  for (std::int32_t v : {2, 1, 0, 1, 1, 2, 3}) put(out, v);  // type 2, 1 element, 0 tags
  p2_at = out.size();
  if (with_p2)
    for (std::int32_t v : {9, 1, 0, 2, 1, 2, 3, 4, 5, 6}) put(out, v);
  return out + "\n$EndElements\n";
}

std::string binary_msh_v4(bool with_p2, std::size_t& p2_at) {
  std::string out = "$MeshFormat\n4.1 1 8\n";
  put(out, std::int32_t{1});
  out += "\n$EndMeshFormat\n$Nodes\n";
  for (std::uint64_t v : {1, 6, 1, 6}) put(out, v);  // blocks, nodes, smallest and largest tag
  for (std::int32_t v : {2, 1, 0}) put(out, v);      // dimension, entity, not parametric
  put(out, std::uint64_t{6});
  for (std::uint64_t tag = 1; tag <= 6; ++tag) put(out, tag);
  const double xyz[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}};
  for (const auto& p : xyz)
    for (double c : p) put(out, c);
  out += "\n$EndNodes\n$Elements\n";
  const std::uint64_t blocks = with_p2 ? 2 : 1;
  for (std::uint64_t v : {blocks, blocks, std::uint64_t{1}, blocks}) put(out, v);
  for (std::int32_t v : {2, 1, 2}) put(out, v);  // dimension, entity, type 2
  put(out, std::uint64_t{1});
  for (std::uint64_t v : {1, 1, 2, 3}) put(out, v);
  if (with_p2) {
    for (std::int32_t v : {2, 1}) put(out, v);
    p2_at = out.size();
    put(out, std::int32_t{9});
    put(out, std::uint64_t{1});
    for (std::uint64_t v : {2, 1, 2, 3, 4, 5, 6}) put(out, v);
  }
  return out + "\n$EndElements\n";
}

}  // namespace

TEST(SurfaceIoNoSilentLoss, BinaryGmshRefusesSurfaceElementsItCannotRead) {
  std::size_t at = 0;
  EXPECT_EQ(parse_surface<2>(binary_msh_v2(false, at), SurfaceFormat::gmsh, "ok2.msh").element_count(), 1);
  EXPECT_EQ(parse_surface<2>(binary_msh_v4(false, at), SurfaceFormat::gmsh, "ok4.msh").element_count(), 1);
  const std::string v2 = binary_msh_v2(true, at);
  expect_refused(v2, SurfaceFormat::gmsh, "p2b.msh", "byte " + std::to_string(at), "type 9");
  const std::string v4 = binary_msh_v4(true, at);
  expect_refused(v4, SurfaceFormat::gmsh, "p2b4.msh", "byte " + std::to_string(at), "type 9");
}
