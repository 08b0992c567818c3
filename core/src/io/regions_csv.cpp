#include "plmap/core/io/regions_csv.hpp"

#include "plmap/core/io/atomic_file.hpp"
#include "plmap/core/regions.hpp"

#include <fmt/format.h>

#include <ostream>

namespace plmap {
namespace {

constexpr std::array<char, 3> axis_names{'x', 'y', 'z'};

template <int d>
void append_header(fmt::memory_buffer& out) {
  const auto add = [&](std::string_view column) {
    out.push_back(',');
    out.append(column);
  };
  out.append(std::string_view("region,domain_element,target_element"));
  for (const char* side : {"domain", "target"}) {
    for (int c = 0; c <= d; ++c) {
      for (int i = 0; i < d; ++i) add(fmt::format("{}_local_{}_xi{}", side, c, i));
    }
  }
  for (const char* side : {"domain", "target"}) {
    for (int c = 0; c <= d; ++c) {
      for (int i = 0; i <= d; ++i) add(fmt::format("{}_world_{}_{}", side, c, axis_names[i]));
    }
  }
  add("domain_measure");
  add("target_measure");
  out.push_back('\n');
}

template <int d>
void append_row(fmt::memory_buffer& out, const RemoteIntersection<d>& ri) {
  auto it = std::back_inserter(out);
  fmt::format_to(it, "{},{},{}", ri.region, ri.domain_element, ri.target_element);
  for (const auto* locals : {&ri.domain_local, &ri.target_local}) {
    for (const auto& xi : *locals) {
      for (int i = 0; i < d; ++i) fmt::format_to(it, ",{}", xi(i));
    }
  }
  for (const auto* worlds : {&ri.domain_world, &ri.target_world}) {
    for (const auto& x : *worlds) {
      for (int i = 0; i <= d; ++i) fmt::format_to(it, ",{}", x(i));
    }
  }
  fmt::format_to(it, ",{},{}\n", ri.domain_measure(), ri.target_measure());
}

}  // namespace

template <int d>
void write_regions_csv(std::ostream& out, const PlMap<d>& map) {
  fmt::memory_buffer buffer;
  append_header<d>(buffer);
  for (Index r = 0; r < map.region_count(); ++r) {
    append_row<d>(buffer, remote_intersection(map, r));
    if (buffer.size() > (1u << 20)) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

template <int d>
void write_regions_csv(const std::filesystem::path& path, const PlMap<d>& map) {
  write_file_atomically(path, [&](std::ostream& out) { write_regions_csv(out, map); }, true);
}

template void write_regions_csv(std::ostream&, const PlMap<1>&);
template void write_regions_csv(std::ostream&, const PlMap<2>&);
template void write_regions_csv(const std::filesystem::path&, const PlMap<1>&);
template void write_regions_csv(const std::filesystem::path&, const PlMap<2>&);

}  // namespace plmap
