// Surface file formats: round trips for every writer/reader pair, hand-written files for every
// reader, a table of malformed inputs with the error each must raise, and atomic writing.
#include "test_surface_io_samples.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/core/io/surface_writer.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <sys/stat.h>

using namespace plmap;
using namespace plmap::surface_io_test;
namespace fs = std::filesystem;

namespace {

/// A directory of the running test's own: CTest runs the tests of this file as parallel
/// processes, and one test's temporary files must not show up in another's directory listing.
fs::path scratch_dir() {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(PLMAP_TEST_BINARY_DIR) / "surface_io_scratch" /
                       (std::string(test->test_suite_name()) + "." + test->name());
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

template <int d>
void expect_same(const Surface<d>& expected, const Surface<d>& actual) {
  ASSERT_EQ(expected.vertex_count(), actual.vertex_count());
  ASSERT_EQ(expected.element_count(), actual.element_count());
  for (Index v = 0; v < expected.vertex_count(); ++v)
    EXPECT_EQ(expected.vertex(v), actual.vertex(v)) << "vertex " << v;
  for (Index t = 0; t < expected.element_count(); ++t)
    EXPECT_EQ(expected.element(t), actual.element(t)) << "element " << t;
}

using Triangles = std::vector<ElementCorners<2>>;

struct RoundTripCase {
  std::string file_name;
  SurfaceWriteOptions options;
  bool float_only;  // the format stores single precision (binary STL)
};

std::vector<RoundTripCase> triangle_round_trip_cases() {
  std::vector<RoundTripCase> cases = {
      {"a.off", {}, false},
      {"a.obj", {}, false},
      {"ascii.stl", {Encoding::ascii, GmshVersion::v4_1}, false},
      {"binary.stl", {Encoding::binary, GmshVersion::v4_1}, true},
      {"default.stl", {}, true},
      {"ascii.ply", {Encoding::ascii, GmshVersion::v4_1}, false},
      {"little.ply", {Encoding::binary, GmshVersion::v4_1}, false},
      {"big.ply", {Encoding::binary_big_endian, GmshVersion::v4_1}, false},
      {"v2.msh", {Encoding::ascii, GmshVersion::v2_2}, false},
      {"v2-binary.msh", {Encoding::binary, GmshVersion::v2_2}, false},
      {"v4.msh", {Encoding::ascii, GmshVersion::v4_1}, false},
      {"v4-binary.msh", {Encoding::binary, GmshVersion::v4_1}, false},
  };
  return cases;
}

TEST(SurfaceIo, TriangleSurfacesRoundTripThroughEveryFormat) {
  for (const auto& c : triangle_round_trip_cases()) {
    SCOPED_TRACE(c.file_name);
    const fs::path path = scratch_dir() / c.file_name;
    // STL renumbers vertices by first appearance and binary STL stores floats: the
    // tetrahedron is built to survive both; the fin (non-float coordinates) is tested elsewhere.
    const std::vector<std::pair<Surface<2>, bool>> surfaces = {{tetrahedron(), true}, {fin(), false}};
    for (const auto& [s, exact_in_float] : surfaces) {
      if (c.float_only && !exact_in_float) continue;
      write_surface(path, s, c.options);
      expect_same(s, read_triangle_surface(path));
    }
  }
}

TEST(SurfaceIo, ReadsAPipeWhoseSizeIsNotKnownAhead) {
  // The reader reads a file with one call of its known size; a pipe has none, and is read in
  // growing pieces: a surface of about 0.9 MB, many times a pipe's buffer and the first piece.
  std::vector<WorldPoint<2>> vertices;
  Triangles triangles;
  const int n = 120;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) vertices.emplace_back(i + 0.1 * j, j - 0.01 * i, 0.001 * i * j);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i, b = a + 1, c = a + n + 1, e = c + 1;
      triangles.push_back({a, b, e});
      triangles.push_back({a, e, c});
    }
  const Surface<2> grid(std::move(vertices), std::move(triangles));
  const fs::path file = scratch_dir() / "grid.off", pipe = scratch_dir() / "grid-pipe.off";
  write_surface(file, grid);
  const std::string bytes = slurp(file);
  ASSERT_GT(bytes.size(), std::size_t{800'000});
  fs::remove(pipe);
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  std::thread writer([&] { spit(pipe, bytes); });
  const Surface<2> read = read_triangle_surface(pipe);
  writer.join();
  expect_same(grid, read);
}

TEST(SurfaceIo, BinaryStlRoundsToFloat) {
  const fs::path path = scratch_dir() / "fin.stl";
  write_surface(path, fin(), {Encoding::binary, GmshVersion::v4_1});
  const auto back = read_triangle_surface(path);
  ASSERT_EQ(back.vertex_count(), fin().vertex_count());
  for (Index v = 0; v < back.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(back.vertex(v)(k), static_cast<double>(static_cast<float>(fin().vertex(v)(k))));
}

TEST(SurfaceIo, CurvesRoundTripThroughEveryFormat) {
  const std::vector<std::pair<std::string, SurfaceWriteOptions>> cases = {
      {"a.curve", {}},
      {"v2.msh", {Encoding::ascii, GmshVersion::v2_2}},
      {"v2-binary.msh", {Encoding::binary, GmshVersion::v2_2}},
      {"v4.msh", {Encoding::ascii, GmshVersion::v4_1}},
      {"v4-binary.msh", {Encoding::binary, GmshVersion::v4_1}},
  };
  for (const auto& [name, options] : cases) {
    SCOPED_TRACE(name);
    const fs::path path = scratch_dir() / ("curve-" + name);
    write_surface(path, polyline(), options);
    expect_same(polyline(), read_curve(path));
  }
}

TEST(SurfaceIo, WritersRefuseWhatTheFormatCannotHold) {
  EXPECT_THROW(format_surface(tetrahedron(), SurfaceFormat::curve), Error);
  EXPECT_THROW(format_surface(polyline(), SurfaceFormat::off), Error);
  EXPECT_THROW(format_surface(tetrahedron(), SurfaceFormat::off, {Encoding::binary, GmshVersion::v4_1}), Error);
  EXPECT_THROW(format_surface(tetrahedron(), SurfaceFormat::stl, {Encoding::binary_big_endian, GmshVersion::v4_1}),
               Error);
  try {
    write_surface(scratch_dir() / "x.unknown", tetrahedron());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.unknown"), std::string::npos);
  }
}

// ---- hand-written files ----

struct HandWritten {
  std::string name;
  SurfaceFormat format;
  std::string content;
  std::vector<WorldPoint<2>> vertices;
  Triangles triangles;
};

TEST(SurfaceIo, ReadsHandWrittenTriangleFiles) {
  const std::vector<WorldPoint<2>> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Triangles two = {{0, 1, 2}, {0, 2, 3}};
  std::vector<WorldPoint<2>> square_plus = square;
  square_plus.push_back({0.5, 2, 0});
  const std::vector<HandWritten> files = {
      {"quad.off", SurfaceFormat::off, off_quad_with_comments, square_plus, {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}}},
      {"mixed.obj", SurfaceFormat::obj, obj_mixed_corners, square, two},
      {"square.stl", SurfaceFormat::stl, stl_ascii_square, square, two},
      {"extras.ply", SurfaceFormat::ply, ply_ascii_with_extras, square, two},
      {"mixed-v2.msh", SurfaceFormat::gmsh, gmsh_v2_mixed, square, two},
      {"blocks-v41.msh", SurfaceFormat::gmsh, gmsh_v41_blocks, square, two},
  };
  for (const auto& f : files) {
    SCOPED_TRACE(f.name);
    const auto s = parse_surface<2>(f.content, f.format, f.name);
    expect_same(Surface<2>(f.vertices, f.triangles), s);
  }
}

TEST(SurfaceIo, ReadsHandWrittenBigEndianBinaryPly) {
  // float coordinates, a uint list with an int count, and an unknown property between them.
  std::string ply =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty short "
      "junk\nproperty float y\nproperty float z\nelement face 1\nproperty list int uint "
      "vertex_indices\nend_header\n";
  auto put = [&](auto value) {
    unsigned char b[sizeof(value)];
    std::memcpy(b, &value, sizeof(value));
    for (std::size_t i = 0; i < sizeof(value); ++i) ply.push_back(static_cast<char>(b[sizeof(value) - 1 - i]));
  };
  const float coords[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0.5f}};
  for (const auto& c : coords) {
    put(c[0]);
    put(std::int16_t{-7});
    put(c[1]);
    put(c[2]);
  }
  put(std::int32_t{3});
  for (std::uint32_t v : {0u, 1u, 2u}) put(v);
  const auto s = parse_surface<2>(ply, SurfaceFormat::ply, "big.ply");
  ASSERT_EQ(s.vertex_count(), 3);
  EXPECT_EQ(s.vertex(2), WorldPoint<2>(0, 2, 0.5));
  EXPECT_EQ(s.element(0), (ElementCorners<2>{0, 1, 2}));
}

TEST(SurfaceIo, StlMergesOnlyExactlyEqualCorners) {
  const std::string stl = std::string(stl_ascii_square) +
                          "solid second\nfacet normal 0 0 1\nouter loop\nvertex 1 1 0\n"
                          "vertex 2 1 0\nvertex 2 2 0\nendloop\nendfacet\n"
                          "facet normal 0 0 1\nouter loop\nvertex 1.0000000001 1 0\n"
                          "vertex 2 2 0\nvertex 1 2 0\nendloop\nendfacet\nendsolid\n";
  const auto s = parse_surface<2>(stl, SurfaceFormat::stl, "two-solids.stl");
  EXPECT_EQ(s.vertex_count(), 8);
  EXPECT_EQ(s.element(2), (ElementCorners<2>{2, 4, 5}));
  EXPECT_EQ(s.element(3), (ElementCorners<2>{6, 5, 7}));
}

TEST(SurfaceIo, PolygonsCanBeRejected) {
  SurfaceReadOptions strict;
  strict.polygons = PolygonPolicy::reject;
  try {
    parse_surface<2>(off_quad_with_comments, SurfaceFormat::off, "quad.off", strict);
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), "quad.off");
    EXPECT_EQ(e.location(), "line 11");
  }
}

TEST(SurfaceIo, ReadsHandWrittenCurves) {
  const Surface<1> triangle({{0, 0}, {1, 0}, {0, 1}}, {{0, 1}, {1, 2}, {2, 0}});
  expect_same(triangle, parse_surface<1>(curve_text_triangle, SurfaceFormat::curve, "t.curve"));
  // The line element of the Gmsh files, without the triangles' extra vertices.
  const Surface<1> segment({{0, 0}, {1, 0}}, {{0, 1}});
  expect_same(segment, parse_surface<1>(gmsh_v2_mixed, SurfaceFormat::gmsh, "mixed-v2.msh"));
  expect_same(segment, parse_surface<1>(gmsh_v41_blocks, SurfaceFormat::gmsh, "blocks-v41.msh"));
}

TEST(SurfaceIo, ReadsTheSampleFilesInTheDataFolder) {
  const fs::path dir = fs::path(PLMAP_TEST_DATA_DIR) / "surfaces";
  int triangle_files = 0, curve_files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path& p = entry.path();
    SCOPED_TRACE(p.string());
    if (p.extension() == ".curve" || p.stem().string().starts_with("curve")) {
      EXPECT_GT(read_curve(p).element_count(), 0);
      ++curve_files;
    } else if (format_from_extension(p)) {
      EXPECT_GT(read_triangle_surface(p).element_count(), 0);
      ++triangle_files;
    }
  }
  EXPECT_GE(triangle_files, 6);
  EXPECT_GE(curve_files, 2);
}

TEST(SurfaceIo, RecognisesFormatsByContentWhenTheExtensionIsUnknown) {
  const fs::path path = scratch_dir() / "mesh.data";
  spit(path, off_quad_with_comments);
  EXPECT_EQ(read_triangle_surface(path).element_count(), 3);
  spit(path, gmsh_v2_mixed);
  EXPECT_EQ(read_curve(path).element_count(), 1);
  spit(path, "nothing recognisable\n");
  EXPECT_THROW(read_triangle_surface(path), ParseError);
}

TEST(SurfaceIo, MissingFileNamesTheFile) {
  try {
    read_triangle_surface(scratch_dir() / "does-not-exist.off");
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_NE(e.file().find("does-not-exist.off"), std::string::npos);
  }
}

TEST(SurfaceIo, DimensionMismatchIsAParseError) {
  EXPECT_THROW(parse_surface<1>(off_quad_with_comments, SurfaceFormat::off, "q.off"), ParseError);
  EXPECT_THROW(parse_surface<2>(curve_text_triangle, SurfaceFormat::curve, "t.curve"), ParseError);
}

TEST(SurfaceIo, CurveNodesOffThePlaneAreRejected) {
  std::string msh = gmsh_v2_mixed;
  msh.replace(msh.find("20 1 0 0"), 8, "20 1 0 3");
  try {
    parse_surface<1>(msh, SurfaceFormat::gmsh, "z.msh");
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.location(), "line 11");
  }
}

TEST(SurfaceIo, SecondOrderGmshMeshesAreRefusedWithAHint) {
  const std::string msh =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
      "4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n$EndNodes\n$Elements\n1\n1 9 0 1 2 3 4 5 6\n"
      "$EndElements\n";
  try {
    parse_surface<2>(msh, SurfaceFormat::gmsh, "p2.msh");
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), "p2.msh");
    EXPECT_NE(std::string(e.what()).find("second-order"), std::string::npos) << e.what();
  }
}

// ---- malformed inputs ----

enum class Expect { parse_error, invalid_surface };

struct Malformed {
  std::string what;
  std::string name;
  SurfaceFormat format;
  int dimension;
  std::string content;
  Expect expect;
  std::string location;  // "line N" or "byte N" that the message must name
};

std::vector<Malformed> malformed_inputs() {
  using F = SurfaceFormat;
  const auto P = Expect::parse_error;
  const auto I = Expect::invalid_surface;
  return {
      {"empty OFF", "e.off", F::off, 2, "", P, "line 1"},
      {"OFF count not a number", "c.off", F::off, 2, "OFF\nthree 1 0\n", P, "line 2"},
      {"OFF truncated vertices", "t.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n", P, "line 5"},
      {"OFF NaN coordinate", "n.off", F::off, 2, "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", P, "line 4"},
      {"OFF inf coordinate", "i.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e999 0\n3 0 1 2\n", P, "line 5"},
      {"OFF index out of range", "r.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", P, "line 6"},
      {"OFF negative index", "m.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", P, "line 6"},
      {"OFF huge count", "h.off", F::off, 2, "OFF\n2000000000 1 0\n0 0 0\n", P, "line 2"},
      {"OFF repeated corner", "d.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", P, "line 6"},
      {"OFF degenerate triangle", "g.off", F::off, 2,
       "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 1 2\n3 0 1 3\n", I, "line 8"},
      {"OFF duplicate triangle", "u.off", F::off, 2,
       "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n", I, "line 6"},
      {"OFF face with two vertices", "f.off", F::off, 2, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", P, "line 6"},
      {"OFF 4-D", "4.off", F::off, 2, "4OFF\n", P, "line 1"},
      {"OBJ index zero", "z.obj", F::obj, 2, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", P, "line 4"},
      {"OBJ index too large", "l.obj", F::obj, 2, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", P, "line 4"},
      {"OBJ relative index too far back", "b.obj", F::obj, 2, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", P, "line 4"},
      {"OBJ bad corner", "c.obj", F::obj, 2, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n", P, "line 4"},
      {"OBJ missing coordinate", "v.obj", F::obj, 2, "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", P, "line 2"},
      {"OBJ without faces", "n.obj", F::obj, 2, "v 0 0 0\n", P, ""},
      {"STL ascii truncated", "t.stl", F::stl, 2, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", P, "line 5"},
      {"STL ascii quad facet", "q.stl", F::stl, 2,
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n", P, "line 7"},
      {"STL ascii NaN", "n.stl", F::stl, 2,
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex NaN 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n",
       P, "line 5"},
      {"STL binary truncated", "b.stl", F::stl, 2, std::string(80, 'x') + std::string("\x02\0\0\0", 4) + std::string(60, '\0'), P,
       "byte 80"},
      {"PLY unknown format", "f.ply", F::ply, 2, "ply\nformat xml 1.0\nend_header\n", P, "line 2"},
      {"PLY no end_header", "h.ply", F::ply, 2, "ply\nformat ascii 1.0\nelement vertex 1\n", P, "line 4"},
      {"PLY missing z", "z.ply", F::ply, 2,
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", P, "line 3"},
      {"PLY count beyond data", "c.ply", F::ply, 2,
       "ply\nformat binary_little_endian 1.0\nelement vertex 100000\nproperty float x\nproperty float y\nproperty float "
       "z\nend_header\n",
       P, "line 3"},
      {"PLY index out of range", "r.ply", F::ply, 2,
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face "
       "1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n",
       P, "line 13"},
      {"PLY non-integer index", "i.ply", F::ply, 2,
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face "
       "1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
       P, "line 13"},
      {"MSH version 4.0", "v.msh", F::gmsh, 2, "$MeshFormat\n4 0 8\n$EndMeshFormat\n", P, "line 2"},
      {"MSH unknown node", "n.msh", F::gmsh, 2,
       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 0 1 2 "
       "4\n$EndElements\n",
       P, "line 12"},
      {"MSH duplicate node tag", "d.msh", F::gmsh, 2,
       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n", P, "line 7"},
      {"MSH missing end", "e.msh", F::gmsh, 2,
       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$Elements\n", P, "line 7"},
      {"MSH v4 block overflow", "o.msh", F::gmsh, 2,
       "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 5\n1\n0 0 0\n$EndNodes\n", P, "line 6"},
      {"MSH infinite coordinate", "i.msh", F::gmsh, 1,
       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 inf 0 0\n$EndNodes\n", P, "line 7"},
      {"curve bad magic", "m.curve", F::curve, 1, "polyline 1\n", P, "line 1"},
      {"curve segment out of range", "r.curve", F::curve, 1,
       "plmap-curve 1\nvertices 2\n0 0\n1 0\nsegments 1\n0 2\n", P, "line 6"},
      {"curve three coordinates", "c.curve", F::curve, 1, "plmap-curve 1\nvertices 1\n0 0 0\n", P, "line 3"},
      {"curve trailing text", "t.curve", F::curve, 1,
       "plmap-curve 1\nvertices 2\n0 0\n1 0\nsegments 1\n0 1\nmore\n", P, "line 7"},
      {"curve zero-length segment", "z.curve", F::curve, 1,
       "plmap-curve 1\nvertices 3\n0 0\n1 0\n1 0\nsegments 2\n0 1\n1 2\n", I, "line 8"},
      {"curve duplicate segment", "u.curve", F::curve, 1,
       "plmap-curve 1\nvertices 2\n0 0\n1 0\nsegments 2\n0 1\n1 0\n", I, "line 6"},
  };
}

TEST(SurfaceIo, MalformedInputsRaiseTypedErrorsNamingFileAndPlace) {
  for (const auto& m : malformed_inputs()) {
    SCOPED_TRACE(m.what);
    try {
      if (m.dimension == 1) parse_surface<1>(m.content, m.format, m.name);
      else parse_surface<2>(m.content, m.format, m.name);
      ADD_FAILURE() << "no error raised";
    } catch (const ParseError& e) {
      EXPECT_EQ(m.expect, Expect::parse_error) << e.what();
      EXPECT_EQ(e.file(), m.name);
      EXPECT_EQ(e.location(), m.location) << e.what();
    } catch (const InvalidSurfaceError& e) {
      EXPECT_EQ(m.expect, Expect::invalid_surface) << e.what();
      EXPECT_TRUE(std::string(e.what()).starts_with(m.name + ":" + m.location + ":")) << e.what();
    }
  }
}

TEST(SurfaceIo, NonManifoldAndBoundedSurfacesLoad) {
  const auto s = parse_surface<2>(format_surface(fin(), SurfaceFormat::off), SurfaceFormat::off, "fin.off");
  EXPECT_EQ(s.edge_elements(s.find_edge(0, 1)).size(), 3u);
  EXPECT_TRUE(s.is_boundary_vertex(2));
}

// ---- atomic writing ----

TEST(SurfaceIo, AFailedWriteLeavesTheOldFileUntouched) {
  const fs::path path = scratch_dir() / "keep.ply";
  write_surface(path, tetrahedron(), {Encoding::ascii, GmshVersion::v4_1});
  const std::string before = slurp(path);
  // OFF has no binary form: refused before anything is written... and a write into a
  // missing directory fails without creating anything.
  EXPECT_THROW(write_surface(scratch_dir() / "keep.off", tetrahedron(), {Encoding::binary, GmshVersion::v4_1}), Error);
  EXPECT_FALSE(fs::exists(scratch_dir() / "keep.off"));
  EXPECT_THROW(write_surface(scratch_dir() / "no-such-dir" / "x.ply", tetrahedron()), Error);
  // Overwriting replaces the content completely and leaves no temporary file behind.
  write_surface(path, fin(), {Encoding::ascii, GmshVersion::v4_1});
  EXPECT_NE(slurp(path), before);
  expect_same(fin(), read_triangle_surface(path));
  for (const auto& entry : fs::directory_iterator(scratch_dir()))
    EXPECT_EQ(entry.path().filename().string().find("tmp"), std::string::npos) << entry.path();
}

}  // namespace
