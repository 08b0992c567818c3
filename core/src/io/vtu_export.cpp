#include "plmap/core/io/vtu_export.hpp"

#include "plmap/core/errors.hpp"
#include "plmap/core/io/atomic_file.hpp"
#include "plmap/core/regions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <ostream>
#include <string>
#include <system_error>
#include <tuple>
#include <variant>

namespace plmap {
namespace {

// VTK cell type codes (vtkCellType.h).
constexpr std::uint8_t vtk_line = 3;
constexpr std::uint8_t vtk_triangle = 5;

template <int d>
constexpr std::uint8_t vtk_simplex_type() {
  return d == 1 ? vtk_line : vtk_triangle;
}

/// A named per-point or per-cell array, either integral (written as Int32) or real (Float64).
struct DataArray {
  std::string name;
  std::variant<std::vector<std::int32_t>, std::vector<double>> values;
};

/// The content of one .vtu file, filled by the builders below and serialized by write_vtu.
struct UnstructuredGrid {
  std::vector<std::array<double, 3>> points;
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets;  ///< end of each cell in `connectivity`
  std::vector<std::uint8_t> types;
  std::vector<DataArray> point_data;
  std::vector<DataArray> cell_data;
  std::string comment;  ///< explains codes used in the arrays; written as an XML comment

  template <int d>
  void add_point(const WorldPoint<d>& x) {
    std::array<double, 3> p{0.0, 0.0, 0.0};
    for (int i = 0; i <= d; ++i) p[i] = x(i);
    points.push_back(p);
  }
  void add_cell(std::uint8_t type, std::initializer_list<std::int64_t> corners) {
    connectivity.insert(connectivity.end(), corners.begin(), corners.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(type);
  }
  template <int d>
  void add_simplex(const std::array<Index, d + 1>& corners) {
    for (Index c : corners) connectivity.push_back(c);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(vtk_simplex_type<d>());
  }
};

using Buffer = fmt::memory_buffer;

template <class T>
void append_values(Buffer& out, const std::vector<T>& values) {
  // Twelve values per line keeps the file readable in an editor.
  for (std::size_t i = 0; i < values.size(); ++i) {
    fmt::format_to(std::back_inserter(out), "{}{}", i % 12 == 0 ? "\n          " : " ",
                   static_cast<std::conditional_t<std::is_same_v<T, std::uint8_t>, int, T>>(
                       values[i]));
  }
  out.append(std::string_view("\n        "));
}

void append_data_array(Buffer& out, const DataArray& a) {
  const bool integral = std::holds_alternative<std::vector<std::int32_t>>(a.values);
  fmt::format_to(std::back_inserter(out),
                 "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"1\" "
                 "format=\"ascii\">",
                 integral ? "Int32" : "Float64", a.name);
  std::visit([&](const auto& values) { append_values(out, values); }, a.values);
  out.append(std::string_view("</DataArray>\n"));
}

void append_data_section(Buffer& out, std::string_view tag, const std::vector<DataArray>& arrays) {
  if (arrays.empty()) {
    fmt::format_to(std::back_inserter(out), "      <{}/>\n", tag);
    return;
  }
  fmt::format_to(std::back_inserter(out), "      <{} Scalars=\"{}\">\n", tag, arrays.front().name);
  for (const auto& a : arrays) append_data_array(out, a);
  fmt::format_to(std::back_inserter(out), "      </{}>\n", tag);
}

void write_vtu(const std::filesystem::path& path, const UnstructuredGrid& g) {
  Buffer out;
  out.append(std::string_view(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"));
  if (!g.comment.empty()) fmt::format_to(std::back_inserter(out), "  <!-- {} -->\n", g.comment);
  fmt::format_to(std::back_inserter(out),
                 "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 g.points.size(), g.types.size());
  append_data_section(out, "PointData", g.point_data);
  append_data_section(out, "CellData", g.cell_data);
  out.append(std::string_view(
      "      <Points>\n"
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">"));
  for (const auto& p : g.points) {
    fmt::format_to(std::back_inserter(out), "\n          {} {} {}", p[0], p[1], p[2]);
  }
  out.append(std::string_view("\n        </DataArray>\n      </Points>\n      <Cells>\n"));
  out.append(std::string_view(
      "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"));
  append_values(out, g.connectivity);
  out.append(std::string_view(
      "</DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"));
  append_values(out, g.offsets);
  out.append(std::string_view(
      "</DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"));
  append_values(out, g.types);
  out.append(std::string_view(
      "</DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n"));
  write_file_atomically(
      path, [&](std::ostream& os) { os.write(out.data(), static_cast<std::streamsize>(out.size())); },
      true);
}

std::vector<std::int32_t> iota_ids(std::size_t n) {
  std::vector<std::int32_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::int32_t>(i);
  return ids;
}

template <int d>
UnstructuredGrid surface_grid(const Surface<d>& surface) {
  UnstructuredGrid g;
  for (const auto& x : surface.vertices()) g.add_point<d>(x);
  for (const auto& corners : surface.elements()) g.add_simplex<d>(corners);
  g.point_data.push_back({"vertex", iota_ids(surface.vertices().size())});
  g.cell_data.push_back({"element", iota_ids(surface.elements().size())});
  return g;
}

template <int d>
UnstructuredGrid domain_grid(const PlMap<d>& map) {
  UnstructuredGrid g = surface_grid(map.domain());
  const Index elements = map.domain().element_count();
  std::vector<std::int32_t> node_count(elements), region_count(elements);
  for (Index t = 0; t < elements; ++t) {
    node_count[t] = map.nodes_end(t) - map.nodes_begin(t);
    region_count[t] = map.regions_end(t) - map.regions_begin(t);
  }
  g.cell_data.push_back({"node_count", std::move(node_count)});
  g.cell_data.push_back({"region_count", std::move(region_count)});
  return g;
}

template <int d>
UnstructuredGrid graph_grid(const PlMap<d>& map) {
  const auto& m = map.data();
  UnstructuredGrid g;
  g.comment =
      "node_type: 0 corner, 1 touching, 2 intersection, 3 ghost, 4 interior; "
      "edge_kind: 0 closure, 1 target_edge";
  const Index nodes = map.node_count();
  std::vector<std::int32_t> node_type(nodes), node_element(nodes), node_target(nodes);
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
      g.add_point<d>(map.domain().world_position(t, m.node_position[n]));
      node_type[n] = static_cast<std::int32_t>(m.node_type[n]);
      node_element[n] = t;
      node_target[n] = m.node_target[n];
    }
  }
  // Each undirected edge appears in the neighbour lists of both endpoints; keep one copy.
  std::vector<std::tuple<Index, Index, GraphEdgeKind>> edges;
  edges.reserve(m.neighbor.size() / 2);
  for (Index n = 0; n < nodes; ++n) {
    for (Index i = m.neighbor_begin[n]; i < m.neighbor_begin[n + 1]; ++i) {
      const Index other = m.neighbor[i];
      if (other == n) continue;
      edges.emplace_back(std::min(n, other), std::max(n, other), m.neighbor_edge_kind[i]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const auto& a, const auto& b) {
                            return std::get<0>(a) == std::get<0>(b) &&
                                   std::get<1>(a) == std::get<1>(b);
                          }),
              edges.end());
  std::vector<std::int32_t> edge_kind, edge_element;
  edge_kind.reserve(edges.size());
  edge_element.reserve(edges.size());
  for (const auto& [a, b, kind] : edges) {
    g.add_cell(vtk_line, {a, b});
    edge_kind.push_back(static_cast<std::int32_t>(kind));
    edge_element.push_back(node_element[a]);
  }
  g.point_data.push_back({"node_type", std::move(node_type)});
  g.point_data.push_back({"node", iota_ids(static_cast<std::size_t>(nodes))});
  g.point_data.push_back({"element", std::move(node_element)});
  g.point_data.push_back({"node_target", std::move(node_target)});
  g.cell_data.push_back({"edge_kind", std::move(edge_kind)});
  g.cell_data.push_back({"element", std::move(edge_element)});
  return g;
}

/// The regions as separate simplices (no shared points, so that cell data stays sharp), placed
/// on S1 (`on_target` false) or at their images on S2.
template <int d>
UnstructuredGrid region_grid(const std::vector<RemoteIntersection<d>>& regions, bool on_target) {
  UnstructuredGrid g;
  std::vector<std::int32_t> region, domain_element, target_element;
  std::vector<double> domain_measure, target_measure;
  for (const auto& ri : regions) {
    std::array<Index, d + 1> corners;
    for (int i = 0; i <= d; ++i) {
      corners[i] = static_cast<Index>(g.points.size());
      g.add_point<d>(on_target ? ri.target_world[i] : ri.domain_world[i]);
    }
    g.add_simplex<d>(corners);
    region.push_back(ri.region);
    domain_element.push_back(ri.domain_element);
    target_element.push_back(ri.target_element);
    domain_measure.push_back(ri.domain_measure());
    target_measure.push_back(ri.target_measure());
  }
  g.cell_data.push_back({"region", std::move(region)});
  g.cell_data.push_back({"domain_element", std::move(domain_element)});
  g.cell_data.push_back({"target_element", std::move(target_element)});
  g.cell_data.push_back({"domain_measure", std::move(domain_measure)});
  g.cell_data.push_back({"target_measure", std::move(target_measure)});
  return g;
}

void write_collection(const std::filesystem::path& path,
                      const std::vector<std::filesystem::path>& parts) {
  Buffer out;
  out.append(std::string_view(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n"));
  for (std::size_t i = 0; i < parts.size(); ++i) {
    fmt::format_to(std::back_inserter(out),
                   "    <DataSet timestep=\"0\" group=\"\" part=\"{}\" name=\"{}\" file=\"{}\"/>\n",
                   i, parts[i].stem().string(), parts[i].filename().string());
  }
  out.append(std::string_view("  </Collection>\n</VTKFile>\n"));
  write_file_atomically(
      path, [&](std::ostream& os) { os.write(out.data(), static_cast<std::streamsize>(out.size())); },
      true);
}

}  // namespace

template <int d>
std::vector<std::filesystem::path> export_vtu(const PlMap<d>& map,
                                              const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw Error(fmt::format("{}: cannot create directory: {}", directory.string(), error.message()));
  }
  const auto regions = remote_intersections(map);
  std::vector<std::filesystem::path> written;
  const auto emit = [&](const char* name, const UnstructuredGrid& grid) {
    written.push_back(directory / name);
    write_vtu(written.back(), grid);
  };
  emit("domain.vtu", domain_grid(map));
  emit("target.vtu", surface_grid(map.target()));
  emit("graph.vtu", graph_grid(map));
  emit("regions.vtu", region_grid<d>(regions, false));
  emit("images.vtu", region_grid<d>(regions, true));
  const auto collection = directory / "map.pvd";
  write_collection(collection, written);
  written.push_back(collection);
  return written;
}

template <int d>
void write_regions_vtu(const std::filesystem::path& path, const PlMap<d>& map) {
  write_vtu(path, region_grid<d>(remote_intersections(map), false));
}

template void write_regions_vtu(const std::filesystem::path&, const PlMap<1>&);
template void write_regions_vtu(const std::filesystem::path&, const PlMap<2>&);

template std::vector<std::filesystem::path> export_vtu(const PlMap<1>&,
                                                       const std::filesystem::path&);
template std::vector<std::filesystem::path> export_vtu(const PlMap<2>&,
                                                       const std::filesystem::path&);

}  // namespace plmap
