#include "whole_file.hpp"

#include <plmap/core/huge_page_allocator.hpp>

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace plmap::io_detail {

namespace {

/// The rest of a stream whose size is unknown, in pieces that double (at most one copy of
/// each byte per doubling, as a growing string would do, but only where it cannot be avoided).
FileBytes read_unsized(std::ifstream& in, const std::filesystem::path& path) {
  FileBytes bytes;
  std::size_t capacity = std::size_t{1} << 16;
  bytes.data = std::make_unique_for_overwrite<char[]>(capacity);
  while (in) {
    if (bytes.size == capacity) {
      auto larger = std::make_unique_for_overwrite<char[]>(capacity * 2);
      std::memcpy(larger.get(), bytes.data.get(), bytes.size);
      bytes.data = std::move(larger);
      capacity *= 2;
    }
    in.read(bytes.data.get() + bytes.size, static_cast<std::streamsize>(capacity - bytes.size));
    bytes.size += static_cast<std::size_t>(in.gcount());
  }
  if (in.bad()) throw ParseError(path.string(), "", "read error");
  return bytes;
}

}  // namespace

FileBytes read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ParseError(path.string(), "",
                     fmt::format("cannot open: {}", std::error_code(errno, std::generic_category()).message()));
  }
  in.seekg(0, std::ios::end);
  const std::streamoff size = in ? std::streamoff(in.tellg()) : std::streamoff(-1);
  if (size < 0) {  // not seekable (a pipe): read what comes
    in.clear();
    return read_unsized(in, path);
  }
  in.seekg(0);
  FileBytes bytes;
  bytes.size = static_cast<std::size_t>(size);
  bytes.data = std::make_unique_for_overwrite<char[]>(std::max<std::size_t>(bytes.size, 1));
  back_pages(bytes.data.get(), bytes.size);  // filled next: backed in one call, not page by page
  in.read(bytes.data.get(), size);
  if (in.gcount() != size) throw ParseError(path.string(), "", "read error (the file changed while being read?)");
  return bytes;
}

}  // namespace plmap::io_detail
