// The temporary files of write_file_atomically: recognisable names beside the target, removal of
// those a dead process left behind, removal on SIGINT/SIGTERM, and messages that name the
// user's file rather than the temporary (issue 12).

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <ostream>
#include <set>
#include <string>

namespace plmap {
namespace {

using namespace test_maps;

std::string this_host() {
  std::array<char, 256> buffer{};
  if (::gethostname(buffer.data(), buffer.size() - 1) != 0 || buffer[0] == '\0') return "host";
  return buffer.data();
}

std::set<std::string> names_in(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.insert(entry.path().filename().string());
  return names;
}

/// The id of a process that has ended and been reaped: no process has it (until the system
/// hands it out again, which takes a full cycle of process ids).
pid_t ended_process_id() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

/// Runs `body` in a child process and returns its wait status.
template <class Body>
int status_of_child(Body body) {
  const pid_t child = ::fork();
  if (child == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

TEST(AtomicFileTemporaries, NamesAreRecognisableAndBesideTheTarget) {
  const auto dir = scratch_directory("temporary_names");
  const TemporaryFile plain(dir / "result.plmap");
  const TemporaryFile picture(dir / "result.png", ".svg");
  const std::string prefix = ".result.plmap.plmap-tmp-" + this_host() + "-" + std::to_string(::getpid()) + "-";
  EXPECT_EQ(plain.path().parent_path(), dir);
  EXPECT_EQ(plain.path().filename().string().rfind(prefix, 0), 0u) << plain.path();
  EXPECT_EQ(picture.path().extension(), ".svg");
  EXPECT_NE(plain.path(), TemporaryFile(dir / "result.plmap").path()) << "names must not repeat";
  // A long target name is cut, so that the temporary's name stays a valid file name.
  const TemporaryFile long_one(dir / (std::string(240, 'n') + ".plmap"));
  EXPECT_LT(long_one.path().filename().string().size(), 255u);
}

TEST(AtomicFileTemporaries, RemovedUnlessReleased) {
  const auto dir = scratch_directory("temporary_release");
  std::filesystem::path dropped, kept;
  {
    const TemporaryFile a(dir / "a.txt");
    dropped = a.path();
    write_bytes(dropped, "x");
    TemporaryFile b(dir / "b.txt");
    kept = b.path();
    write_bytes(kept, "y");
    b.release();
  }
  EXPECT_FALSE(std::filesystem::exists(dropped));
  EXPECT_TRUE(std::filesystem::exists(kept));
}

TEST(AtomicFileTemporaries, StaleOnesOfEndedProcessesAreRemovedOthersStay) {
  const auto dir = scratch_directory("temporary_stale");
  const std::string host = this_host();
  const std::string of_target = ".map.plmap.plmap-tmp-" + host + "-";
  const std::string stale = of_target + std::to_string(ended_process_id()) + "-0";
  const std::string stale_png = of_target + std::to_string(ended_process_id()) + "-3.png";
  const std::string mine = of_target + std::to_string(::getpid()) + "-7";
  const std::string parents = of_target + std::to_string(::getppid()) + "-0";
  const std::string other_host = ".map.plmap.plmap-tmp-elsewhere-" + std::to_string(ended_process_id()) + "-0";
  const std::string other_target = ".mop.plmap.plmap-tmp-" + host + "-" + std::to_string(ended_process_id()) + "-0";
  const std::string not_a_pid = of_target + "abc-0";
  for (const auto& name : {stale, stale_png, mine, parents, other_host, other_target, not_a_pid})
    write_bytes(dir / name, "half");

  write_file_atomically(dir / "map.plmap", [](std::ostream& out) { out << "whole"; }, false);

  const std::set<std::string> expected = {"map.plmap", mine,         parents,
                                          other_host,  other_target, not_a_pid};
  EXPECT_EQ(names_in(dir), expected);
  EXPECT_EQ(read_bytes(dir / "map.plmap"), "whole");
}

TEST(AtomicFileTemporaries, ErrorsNameTheTargetNotTheTemporary) {
  const auto dir = scratch_directory("temporary_errors");
  write_bytes(dir / "plain_file", "not a directory");
  const std::filesystem::path targets[] = {dir / "missing" / "out.vtu", dir / "plain_file" / "out.vtu",
                                           "/proc/out.vtu"};
  for (const auto& target : targets) {
    try {
      write_file_atomically(target, [](std::ostream& out) { out << "x"; }, false);
      ADD_FAILURE() << "expected plmap::Error for " << target;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(target.string() + ": cannot write", 0), 0u) << message;
      EXPECT_EQ(message.find("plmap-tmp"), std::string::npos) << message;
    }
  }
  EXPECT_EQ(names_in(dir), std::set<std::string>{"plain_file"});
}

TEST(AtomicFileTemporaries, ATerminatingSignalRemovesTheTemporaryBeingWritten) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    const auto dir = scratch_directory("temporary_signal_" + std::to_string(signal_number));
    const auto target = dir / "out.plmap";
    write_bytes(target, "previous");
    const int status = status_of_child([&] {
      remove_temporaries_on_signals();
      write_file_atomically(
          target,
          [&](std::ostream& out) {
            out << "half of the new content" << std::flush;
            ::raise(signal_number);
          },
          false);
    });
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child should end by the signal, status " << status;
    EXPECT_EQ(WTERMSIG(status), signal_number);
    EXPECT_EQ(names_in(dir), std::set<std::string>{"out.plmap"});
    EXPECT_EQ(read_bytes(target), "previous");
  }
}

TEST(AtomicFileTemporaries, AnIgnoredSignalStaysIgnored) {
  const auto dir = scratch_directory("temporary_ignored");
  const auto target = dir / "out.plmap";
  const int status = status_of_child([&] {
    ::signal(SIGHUP, SIG_IGN);  // as under nohup
    remove_temporaries_on_signals();
    write_file_atomically(
        target,
        [](std::ostream& out) {
          out << "complete" << std::flush;
          ::raise(SIGHUP);
        },
        false);
  });
  ASSERT_TRUE(WIFEXITED(status)) << "SIGHUP was ignored before, so it must not end the write";
  EXPECT_EQ(read_bytes(target), "complete");
  EXPECT_EQ(names_in(dir), std::set<std::string>{"out.plmap"});
}

}  // namespace
}  // namespace plmap
