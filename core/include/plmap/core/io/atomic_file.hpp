#pragma once
/// \file
/// Writing a file so that readers never see it half-written: the content goes to a temporary
/// file in the target's directory, is flushed to disk, and only then renamed over the target.
/// If anything fails (the writer throws, the disk is full), the previous file stays untouched.

#include <filesystem>
#include <functional>
#include <iosfwd>

namespace plmap {

/// Writes `path` atomically. `writer` streams the whole content into the given stream; `binary`
/// opens the temporary file in binary mode. Throws plmap::Error naming the file if the temporary
/// file cannot be created, written, synced or renamed; rethrows whatever `writer` throws. In
/// both cases the temporary file is removed and `path` is unchanged.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer, bool binary);

}  // namespace plmap
