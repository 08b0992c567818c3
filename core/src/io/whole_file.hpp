#pragma once
/// \file
/// A whole input file in one buffer, for the readers that parse from memory (surfaces, maps).
///
/// Private to core.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string_view>

namespace plmap::io_detail {

/// The bytes of a file, read with one call where the file's size is known: a surface or map is
/// parsed from memory, and this is the one copy of it (no zero-filling, no stream buffering, no
/// string that doubles and copies itself as it grows). Not on huge pages: on the virtual machine
/// measured (docs/benchmarks.md, "Binary map files"), first touches of fresh 2 MiB pages cost
/// more system time than the 4 KiB faults they save.
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

/// Reads `path` whole. A file whose size cannot be told in advance (a pipe, /dev/stdin on a
/// terminal) is read in growing pieces. Throws ParseError naming the file when it cannot be
/// opened or read.
FileBytes read_whole_file(const std::filesystem::path& path);

}  // namespace plmap::io_detail
