// write_file_atomically: the target is replaced only by a complete file; a failing writer leaves
// the old content and no temporary file behind.

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>

#include <gtest/gtest.h>

#include <ostream>
#include <stdexcept>

namespace plmap {
namespace {

using namespace test_maps;

std::ptrdiff_t entries_in(const std::filesystem::path& dir) {
  return std::distance(std::filesystem::directory_iterator(dir),
                       std::filesystem::directory_iterator());
}

TEST(AtomicFile, WritesAndReplacesContent) {
  const auto dir = scratch_directory("atomic_replace");
  const auto path = dir / "file.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "first\n"; }, false);
  EXPECT_EQ(read_bytes(path), "first\n");
  write_file_atomically(path, [](std::ostream& out) { out << "second"; }, true);
  EXPECT_EQ(read_bytes(path), "second");
  EXPECT_EQ(entries_in(dir), 1);
}

TEST(AtomicFile, FailingWriterLeavesTheOldFileAndNoTemporary) {
  const auto dir = scratch_directory("atomic_failure");
  const auto path = dir / "file.txt";
  write_bytes(path, "old content");
  EXPECT_THROW(write_file_atomically(
                   path,
                   [](std::ostream& out) {
                     out << "half of the new";
                     throw std::runtime_error("writer failed midway");
                   },
                   false),
               std::runtime_error);
  EXPECT_EQ(read_bytes(path), "old content");
  EXPECT_EQ(entries_in(dir), 1);
}

TEST(AtomicFile, MissingDirectoryIsATypedErrorNamingTheFile) {
  const auto path = scratch_directory("atomic_missing") / "no" / "such" / "dir" / "file.txt";
  try {
    write_file_atomically(path, [](std::ostream& out) { out << "x"; }, false);
    FAIL() << "expected plmap::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("file.txt"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace plmap
