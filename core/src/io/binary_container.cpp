#include "binary_container.hpp"

#include "plmap/core/errors.hpp"
#include "plmap/core/io/map_file_binary.hpp"
#include "plmap/core/parallel_ranges.hpp"

#include <fmt/format.h>
#include <zlib.h>
#if defined(PLMAP_HAVE_LIBDEFLATE)
#include <libdeflate.h>
#endif

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <ostream>

namespace plmap::binary {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary map format stores the in-memory bytes, which must be little-endian");

template <class T>
T load_le(const char* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

template <class T>
void append_le(std::string& out, T value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  out.append(bytes, sizeof value);
}

std::uint64_t align_up(std::uint64_t offset) {
  return (offset + array_alignment - 1) / array_alignment * array_alignment;
}

/// Largest table of contents a reader accepts: a map's table is a few kilobytes, so anything
/// beyond this is damage, and refusing it bounds what a corrupt header makes us allocate.
constexpr std::uint64_t max_table_bytes = 1u << 20;

struct Header {
  std::uint32_t version = 0;
  std::uint32_t table_crc = 0;
  std::uint64_t table_bytes = 0;
  std::uint64_t file_bytes = 0;
};

Header read_header(std::string_view content, const std::string& file) {
  if (content.size() < binary_map_magic.size() || content.substr(0, binary_map_magic.size()) != binary_map_magic) {
    throw ParseError(file, "", "not a binary plmap map file (wrong magic bytes)");
  }
  if (content.size() < header_bytes) {
    throw ParseError(file, "", fmt::format("truncated: {} bytes, shorter than the {}-byte header",
                                           content.size(), header_bytes));
  }
  Header h;
  h.version = load_le<std::uint32_t>(content.data() + 8);
  h.table_crc = load_le<std::uint32_t>(content.data() + 12);
  h.table_bytes = load_le<std::uint64_t>(content.data() + 16);
  h.file_bytes = load_le<std::uint64_t>(content.data() + 24);
  if (h.version < oldest_binary_map_version || h.version > binary_map_version) {
    throw ParseError(file, "header",
                     fmt::format("unsupported binary map version {} (this build reads versions {} to {})",
                                 h.version, oldest_binary_map_version, binary_map_version));
  }
  if (h.table_bytes == 0 || h.table_bytes > max_table_bytes) {
    throw ParseError(file, "header",
                     fmt::format("table of contents length {} is outside [1, {}] (damaged header)",
                                 h.table_bytes, max_table_bytes));
  }
  return h;
}

nlohmann::json parse_table(std::string_view content, const Header& h, const std::string& file,
                           bool verify_checksum = true) {
  if (content.size() < header_bytes + h.table_bytes) {
    throw ParseError(file, "", fmt::format("truncated: {} bytes, the table of contents ends at byte {}",
                                           content.size(), header_bytes + h.table_bytes));
  }
  const std::string_view table = content.substr(header_bytes, h.table_bytes);
  if (verify_checksum && crc32_of(table.data(), table.size()) != h.table_crc) {
    throw ParseError(file, "table of contents", "checksum mismatch (the file is damaged)");
  }
  nlohmann::json toc = nlohmann::json::parse(table, nullptr, false);
  if (toc.is_discarded() || !toc.is_object()) {
    throw ParseError(file, "table of contents", "not a JSON object (the file is damaged)");
  }
  return toc;
}

}  // namespace

std::uint32_t crc32_of(const void* data, std::size_t size) {
#if defined(PLMAP_HAVE_LIBDEFLATE)
  // The same CRC-32 (the checksums are part of the file format), computed with the carry-less
  // multiply instructions where the CPU has them.
  return ::libdeflate_crc32(0, data, size);
#else
  return static_cast<std::uint32_t>(
      ::crc32_z(0L, static_cast<const Bytef*>(data), static_cast<z_size_t>(size)));
#endif
}

namespace {

/// Bytes per checksum piece: large enough that combining (a few microseconds each) is noise,
/// small enough that a 100 MB array spreads over every thread.
constexpr std::size_t crc_piece_bytes = std::size_t{4} << 20;

}  // namespace

std::vector<std::uint32_t> crc32_of_each(const std::vector<std::pair<const void*, std::size_t>>& ranges,
                                         unsigned threads) {
  // Cut every range into pieces; piece i covers bytes [start, start + size) of range `range`.
  struct Piece {
    std::size_t range, start, size;
  };
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const std::size_t bytes = ranges[i].second;
    for (std::size_t start = 0; start == 0 || start < bytes; start += crc_piece_bytes) {
      pieces.push_back({i, start, std::min(crc_piece_bytes, bytes - start)});
    }
  }
  std::vector<std::uint32_t> piece_crc(pieces.size());
  parallel_for_pieces_of_size(pieces.size(), 1, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Piece& p = pieces[k];
      piece_crc[k] = crc32_of(static_cast<const unsigned char*>(ranges[p.range].first) + p.start, p.size);
    }
  });
  std::vector<std::uint32_t> out(ranges.size());
  std::vector<bool> started(ranges.size(), false);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& p = pieces[k];
    out[p.range] = !started[p.range]
                       ? piece_crc[k]
                       : static_cast<std::uint32_t>(::crc32_combine(out[p.range], piece_crc[k],
                                                                    static_cast<z_off_t>(p.size)));
    started[p.range] = true;
  }
  return out;
}

std::uint32_t crc32_parallel(const void* data, std::size_t size, unsigned threads) {
  return crc32_of_each({{data, size}}, threads).front();
}

std::size_t dtype_size(std::string_view dtype) {
  if (dtype == "<f8") return 8;
  if (dtype == "<i4" || dtype == "<u4") return 4;
  if (dtype == "<u2") return 2;
  if (dtype == "|u1" || dtype == "|i1") return 1;
  return 0;
}

void write_container(std::ostream& out, nlohmann::json toc, const std::vector<OutArray>& arrays,
                     const ProgressCallback& progress, unsigned threads) {
  std::vector<std::pair<const void*, std::size_t>> ranges;
  for (const OutArray& a : arrays) ranges.emplace_back(a.data, a.bytes);
  const std::vector<std::uint32_t> crc = crc32_of_each(ranges, threads);
  // The table holds the offsets, whose values depend on the table's length: lay out with a
  // provisional length, and again if the real one crosses the alignment boundary.
  std::uint64_t table_estimate = 0;
  std::string table;
  std::vector<std::uint64_t> offsets(arrays.size());
  std::uint64_t file_bytes = 0;
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::uint64_t offset = align_up(header_bytes + table_estimate);
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < arrays.size(); ++i) {
      const OutArray& a = arrays[i];
      offsets[i] = offset;
      nlohmann::json entry = {{"name", a.name},
                              {"dtype", a.dtype},
                              {"shape", a.shape},
                              {"encoding", a.encoding},
                              {"offset", offset},
                              {"bytes", a.bytes},
                              {"crc32", crc[i]}};
      if (!a.base.empty()) entry["base"] = a.base;
      list.push_back(std::move(entry));
      offset = align_up(offset + a.bytes);
    }
    file_bytes = offset;
    toc["arrays"] = std::move(list);
    table = toc.dump();
    if (align_up(header_bytes + table.size()) == align_up(header_bytes + table_estimate)) break;
    table_estimate = table.size();
  }

  std::string head(binary_map_magic);
  append_le<std::uint32_t>(head, binary_map_version);
  append_le<std::uint32_t>(head, crc32_of(table.data(), table.size()));
  append_le<std::uint64_t>(head, table.size());
  append_le<std::uint64_t>(head, file_bytes);
  head += table;
  std::uint64_t written = head.size();
  out.write(head.data(), static_cast<std::streamsize>(head.size()));
  static const char zeros[array_alignment] = {};
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    out.write(zeros, static_cast<std::streamsize>(offsets[i] - written));
    out.write(static_cast<const char*>(arrays[i].data), static_cast<std::streamsize>(arrays[i].bytes));
    written = offsets[i] + arrays[i].bytes;
    if (i + 1 < arrays.size()) report_progress(progress, "writing map", written, file_bytes);
  }
  out.write(zeros, static_cast<std::streamsize>(file_bytes - written));
  report_progress(progress, "writing map", file_bytes, file_bytes);
}

std::uint64_t Container::table_bytes_from_header(std::string_view head, const std::string& file) {
  return read_header(head, file).table_bytes;
}

nlohmann::json Container::table_only(std::string_view head, const std::string& file) {
  return parse_table(head, read_header(head, file), file);
}

Container::Container(std::string_view content, std::string file, bool verify_table_checksum)
    : content_(content), file_(std::move(file)) {
  const Header h = read_header(content_, file_);
  version_ = h.version;
  toc_ = parse_table(content_, h, file_, verify_table_checksum);
  if (h.file_bytes != content_.size()) {
    fail(h.file_bytes > content_.size()
             ? fmt::format("truncated: {} bytes, the header says {}", content_.size(), h.file_bytes)
             : fmt::format("{} bytes, the header says {} (extra bytes at the end)", content_.size(),
                           h.file_bytes));
  }
  const auto list = toc_.find("arrays");
  if (list == toc_.end() || !list->is_array()) fail("the table of contents has no array list");
  std::uint64_t previous_end = header_bytes + h.table_bytes;
  for (const nlohmann::json& entry : *list) {
    InArray a;
    // Every field is checked for its JSON type before use: the table is untrusted input.
    auto text = [&](const char* key, bool required) -> std::string {
      const auto it = entry.find(key);
      if (it == entry.end()) {
        if (required) fail(fmt::format("an array entry has no '{}'", key));
        return {};
      }
      if (!it->is_string()) fail(fmt::format("an array entry's '{}' is not a string", key));
      return it->get<std::string>();
    };
    auto number = [&](const char* key) -> std::uint64_t {
      const auto it = entry.is_object() ? entry.find(key) : entry.end();
      if (it == entry.end() || !it->is_number_unsigned()) {
        fail(fmt::format("array '{}': '{}' is missing or not a non-negative integer", a.name, key));
      }
      return it->get<std::uint64_t>();
    };
    if (!entry.is_object()) fail("an array entry is not a JSON object");
    a.name = text("name", true);
    a.dtype = text("dtype", true);
    a.encoding = text("encoding", true);
    a.base = text("base", false);
    a.item_bytes = dtype_size(a.dtype);
    if (a.item_bytes == 0) fail(a, fmt::format("unknown dtype '{}'", a.dtype));
    const auto shape = entry.find("shape");
    if (shape == entry.end() || !shape->is_array() || shape->empty() || shape->size() > 3) {
      fail(a, "the shape must be a list of 1 to 3 dimensions");
    }
    a.items = 1;
    for (const nlohmann::json& extent : *shape) {
      if (!extent.is_number_unsigned()) fail(a, "a shape extent is not a non-negative integer");
      const std::uint64_t n = extent.get<std::uint64_t>();
      // Checked before multiplying, so the product cannot overflow.
      if (n != 0 && a.items > content_.size() / n) {
        fail(a, "the shape holds more items than the file has bytes");
      }
      a.shape.push_back(n);
      a.items *= n;
    }
    const std::uint64_t offset = number("offset");
    const std::uint64_t bytes = number("bytes");
    const std::uint64_t crc = number("crc32");
    if (crc > std::numeric_limits<std::uint32_t>::max()) fail(a, "crc32 is not a 32-bit number");
    a.crc32 = static_cast<std::uint32_t>(crc);
    if (bytes != a.items * a.item_bytes) {
      fail(a, fmt::format("{} bytes do not hold the shape's {} items of {}", bytes, a.items, a.dtype));
    }
    if (offset % array_alignment != 0) fail(a, fmt::format("offset {} is not aligned", offset));
    if (offset < previous_end) fail(a, fmt::format("offset {} overlaps what precedes it", offset));
    if (offset > content_.size() || bytes > content_.size() - offset) {
      fail(a, fmt::format("bytes [{}, {}) lie beyond the end of the file ({} bytes)", offset,
                          offset + bytes, content_.size()));
    }
    previous_end = offset + bytes;
    a.data = reinterpret_cast<const unsigned char*>(content_.data()) + offset;
    a.bytes = bytes;
    if (!arrays_.emplace(a.name, a).second) fail(a, "appears twice in the table of contents");
  }
}

const InArray& Container::array(const std::string& name) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) fail(fmt::format("the file has no array '{}'", name));
  return it->second;
}

void Container::verify_checksum(const InArray& a) const {
  if (crc32_of(a.data, a.bytes) != a.crc32) fail(a, "checksum mismatch (the file is damaged)");
}

void Container::verify_all_checksums(unsigned threads) const {
  // In file order (by offset), so that the first mismatch is the one a sequential reader meets.
  std::vector<const InArray*> in_file_order;
  for (const auto& [name, a] : arrays_) in_file_order.push_back(&a);
  std::sort(in_file_order.begin(), in_file_order.end(),
            [](const InArray* x, const InArray* y) { return x->data < y->data; });
  std::vector<std::pair<const void*, std::size_t>> ranges;
  for (const InArray* a : in_file_order) ranges.emplace_back(a->data, a->bytes);
  const std::vector<std::uint32_t> crc = crc32_of_each(ranges, threads);
  for (std::size_t i = 0; i < crc.size(); ++i) {
    if (crc[i] != in_file_order[i]->crc32) fail(*in_file_order[i], "checksum mismatch (the file is damaged)");
  }
}

void Container::fail(const std::string& what) const { throw ParseError(file_, "", what); }

void Container::fail(const InArray& a, const std::string& what) const {
  throw ParseError(file_, fmt::format("array '{}'", a.name), what);
}

}  // namespace plmap::binary
