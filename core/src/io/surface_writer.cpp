#include <plmap/core/io/surface_writer.hpp>

#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <ostream>

namespace plmap {

namespace {

/// Appends a value's bytes in the requested byte order.
template <class T>
void put_binary(std::string& out, T value, bool big_endian) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

/// fmt's "{}" prints the shortest decimal that reads back to the same double.
template <int d>
void put_point(std::string& out, const WorldPoint<d>& p) {
  for (int k = 0; k <= d; ++k) {
    if (k > 0) out += ' ';
    fmt::format_to(std::back_inserter(out), "{}", p(k));
  }
}

Eigen::Vector3d in_space(const WorldPoint<1>& p) { return {p(0), p(1), 0.0}; }
Eigen::Vector3d in_space(const WorldPoint<2>& p) { return p; }

std::string write_off(const Surface<2>& s) {
  std::string out = fmt::format("OFF\n{} {} 0\n", s.vertex_count(), s.element_count());
  for (const auto& p : s.vertices()) {
    put_point<2>(out, p);
    out += '\n';
  }
  for (const auto& e : s.elements()) fmt::format_to(std::back_inserter(out), "3 {} {} {}\n", e[0], e[1], e[2]);
  return out;
}

std::string write_obj(const Surface<2>& s) {
  std::string out = "# written by plmap\n";
  for (const auto& p : s.vertices()) {
    out += "v ";
    put_point<2>(out, p);
    out += '\n';
  }
  for (const auto& e : s.elements())
    fmt::format_to(std::back_inserter(out), "f {} {} {}\n", e[0] + 1, e[1] + 1, e[2] + 1);
  return out;
}

std::string write_stl(const Surface<2>& s, bool binary) {
  std::string out;
  if (binary) {
    std::string header = "binary STL written by plmap";
    header.resize(80, ' ');
    out = header;
    put_binary<std::uint32_t>(out, static_cast<std::uint32_t>(s.element_count()), false);
    for (Index t = 0; t < s.element_count(); ++t) {
      const auto n = s.element_normal(t);
      for (int k = 0; k < 3; ++k) put_binary<float>(out, static_cast<float>(n(k)), false);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) put_binary<float>(out, static_cast<float>(s.corner(t, c)(k)), false);
      put_binary<std::uint16_t>(out, 0, false);
    }
    return out;
  }
  out = "solid plmap\n";
  for (Index t = 0; t < s.element_count(); ++t) {
    out += "facet normal ";
    put_point<2>(out, s.element_normal(t));
    out += "\n outer loop\n";
    for (int c = 0; c < 3; ++c) {
      out += "  vertex ";
      put_point<2>(out, s.corner(t, c));
      out += '\n';
    }
    out += " endloop\nendfacet\n";
  }
  out += "endsolid plmap\n";
  return out;
}

std::string write_ply(const Surface<2>& s, Encoding encoding) {
  const char* format = encoding == Encoding::ascii             ? "ascii"
                       : encoding == Encoding::binary_big_endian ? "binary_big_endian"
                                                                 : "binary_little_endian";
  std::string out = fmt::format(
      "ply\nformat {} 1.0\ncomment written by plmap\nelement vertex {}\nproperty double x\n"
      "property double y\nproperty double z\nelement face {}\n"
      "property list uchar int vertex_indices\nend_header\n",
      format, s.vertex_count(), s.element_count());
  if (encoding == Encoding::ascii) {
    for (const auto& p : s.vertices()) {
      put_point<2>(out, p);
      out += '\n';
    }
    for (const auto& e : s.elements()) fmt::format_to(std::back_inserter(out), "3 {} {} {}\n", e[0], e[1], e[2]);
    return out;
  }
  const bool big = encoding == Encoding::binary_big_endian;
  for (const auto& p : s.vertices())
    for (int k = 0; k < 3; ++k) put_binary<double>(out, p(k), big);
  for (const auto& e : s.elements()) {
    put_binary<std::uint8_t>(out, 3, big);
    for (Index v : e) put_binary<std::int32_t>(out, v, big);
  }
  return out;
}

template <int d>
std::string write_gmsh(const Surface<d>& s, bool binary, GmshVersion version) {
  constexpr int element_type = d == 1 ? 1 : 2;
  const auto nv = static_cast<std::size_t>(s.vertex_count());
  const auto ne = static_cast<std::size_t>(s.element_count());
  const bool v2 = version == GmshVersion::v2_2;
  std::string out = fmt::format("$MeshFormat\n{} {} 8\n", v2 ? "2.2" : "4.1", binary ? 1 : 0);
  if (binary) {
    put_binary<std::int32_t>(out, 1, std::endian::native == std::endian::big);
    out += '\n';
  }
  out += "$EndMeshFormat\n$Nodes\n";
  const bool native_big = std::endian::native == std::endian::big;
  // Gmsh tags start at 1.
  if (v2) {
    fmt::format_to(std::back_inserter(out), "{}\n", nv);
    for (std::size_t i = 0; i < nv; ++i) {
      const Eigen::Vector3d p = in_space(s.vertex(static_cast<Index>(i)));
      if (binary) {
        put_binary<std::int32_t>(out, static_cast<std::int32_t>(i + 1), native_big);
        for (int k = 0; k < 3; ++k) put_binary<double>(out, p(k), native_big);
      } else {
        fmt::format_to(std::back_inserter(out), "{} {} {} {}\n", i + 1, p(0), p(1), p(2));
      }
    }
    if (binary) out += '\n';
    fmt::format_to(std::back_inserter(out), "$EndNodes\n$Elements\n{}\n", ne);
    if (binary) {
      // One block of all elements: type, count, number of tags (2: physical, elementary).
      put_binary<std::int32_t>(out, element_type, native_big);
      put_binary<std::int32_t>(out, static_cast<std::int32_t>(ne), native_big);
      put_binary<std::int32_t>(out, 2, native_big);
    }
    for (std::size_t t = 0; t < ne; ++t) {
      const auto& e = s.element(static_cast<Index>(t));
      if (binary) {
        for (std::int32_t v : {static_cast<std::int32_t>(t + 1), 1, 1}) put_binary<std::int32_t>(out, v, native_big);
        for (Index v : e) put_binary<std::int32_t>(out, v + 1, native_big);
      } else {
        fmt::format_to(std::back_inserter(out), "{} {} 2 1 1", t + 1, element_type);
        for (Index v : e) fmt::format_to(std::back_inserter(out), " {}", v + 1);
        out += '\n';
      }
    }
    if (binary) out += '\n';
    out += "$EndElements\n";
    return out;
  }
  // MSH 4.1: one entity of dimension d holding every node and every element. $Entities is
  // optional in 4.1; Gmsh creates discrete entities for the tags it finds.
  if (binary) {
    for (std::uint64_t v : {std::uint64_t{1}, std::uint64_t{nv}, std::uint64_t{1}, std::uint64_t{nv}})
      put_binary<std::uint64_t>(out, v, native_big);
    for (std::int32_t v : {d, 1, 0}) put_binary<std::int32_t>(out, v, native_big);
    put_binary<std::uint64_t>(out, nv, native_big);
    for (std::size_t i = 0; i < nv; ++i) put_binary<std::uint64_t>(out, i + 1, native_big);
    for (std::size_t i = 0; i < nv; ++i) {
      const Eigen::Vector3d p = in_space(s.vertex(static_cast<Index>(i)));
      for (int k = 0; k < 3; ++k) put_binary<double>(out, p(k), native_big);
    }
    out += "\n$EndNodes\n$Elements\n";
    for (std::uint64_t v : {std::uint64_t{1}, std::uint64_t{ne}, std::uint64_t{1}, std::uint64_t{ne}})
      put_binary<std::uint64_t>(out, v, native_big);
    for (std::int32_t v : {d, 1, element_type}) put_binary<std::int32_t>(out, v, native_big);
    put_binary<std::uint64_t>(out, ne, native_big);
    for (std::size_t t = 0; t < ne; ++t) {
      put_binary<std::uint64_t>(out, t + 1, native_big);
      for (Index v : s.element(static_cast<Index>(t)))
        put_binary<std::uint64_t>(out, static_cast<std::uint64_t>(v) + 1, native_big);
    }
    out += "\n$EndElements\n";
    return out;
  }
  fmt::format_to(std::back_inserter(out), "1 {} 1 {}\n{} 1 0 {}\n", nv, nv, d, nv);
  for (std::size_t i = 0; i < nv; ++i) fmt::format_to(std::back_inserter(out), "{}\n", i + 1);
  for (std::size_t i = 0; i < nv; ++i) {
    const Eigen::Vector3d p = in_space(s.vertex(static_cast<Index>(i)));
    fmt::format_to(std::back_inserter(out), "{} {} {}\n", p(0), p(1), p(2));
  }
  fmt::format_to(std::back_inserter(out), "$EndNodes\n$Elements\n1 {} 1 {}\n{} 1 {} {}\n", ne, ne,
                 d, element_type, ne);
  for (std::size_t t = 0; t < ne; ++t) {
    fmt::format_to(std::back_inserter(out), "{}", t + 1);
    for (Index v : s.element(static_cast<Index>(t))) fmt::format_to(std::back_inserter(out), " {}", v + 1);
    out += '\n';
  }
  out += "$EndElements\n";
  return out;
}

std::string write_curve_text(const Surface<1>& s) {
  std::string out = fmt::format("plmap-curve 1\n# written by plmap\nvertices {}\n", s.vertex_count());
  for (const auto& p : s.vertices()) {
    put_point<1>(out, p);
    out += '\n';
  }
  fmt::format_to(std::back_inserter(out), "segments {}\n", s.element_count());
  for (const auto& e : s.elements()) fmt::format_to(std::back_inserter(out), "{} {}\n", e[0], e[1]);
  return out;
}

[[noreturn]] void unsupported(SurfaceFormat format, std::string_view what) {
  throw Error(fmt::format("the {} writer does not support {}", format_name(format), what));
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
std::string format_surface(const Surface<d>& surface, SurfaceFormat format,
                           const SurfaceWriteOptions& options) {
  if (!format_supports_dimension(format, d))
    unsupported(format, d == 1 ? "curves" : "triangle surfaces");
  const Encoding encoding = options.encoding;
  const bool binary = encoding == Encoding::binary || encoding == Encoding::binary_big_endian;
  if (encoding == Encoding::binary_big_endian && format != SurfaceFormat::ply)
    unsupported(format, "big-endian binary output");
  if (binary && (format == SurfaceFormat::off || format == SurfaceFormat::obj ||
                 format == SurfaceFormat::curve))
    unsupported(format, "binary output");
  if constexpr (d == 2) {
    switch (format) {
      case SurfaceFormat::off: return write_off(surface);
      case SurfaceFormat::obj: return write_obj(surface);
      case SurfaceFormat::stl: return write_stl(surface, encoding != Encoding::ascii);
      case SurfaceFormat::ply:
        return write_ply(surface, encoding == Encoding::format_default ? Encoding::binary : encoding);
      default: break;
    }
  } else {
    if (format == SurfaceFormat::curve) return write_curve_text(surface);
  }
  return write_gmsh<d>(surface, binary, options.gmsh_version);
}

template <int d>
  requires SurfaceDimension<d>
void write_surface(const std::filesystem::path& path, const Surface<d>& surface,
                   const SurfaceWriteOptions& options) {
  const auto format = format_from_extension(path);
  if (!format)
    throw Error(path.string() +
                ": unknown surface format: use the extension .off, .obj, .stl, .ply, .msh or .curve");
  std::string bytes;
  try {
    bytes = format_surface(surface, *format, options);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); },
                        true);
}

template void write_surface<1>(const std::filesystem::path&, const Surface<1>&, const SurfaceWriteOptions&);
template void write_surface<2>(const std::filesystem::path&, const Surface<2>&, const SurfaceWriteOptions&);
template std::string format_surface<1>(const Surface<1>&, SurfaceFormat, const SurfaceWriteOptions&);
template std::string format_surface<2>(const Surface<2>&, SurfaceFormat, const SurfaceWriteOptions&);

}  // namespace plmap
