// The progress callbacks of the long operations (core/progress.hpp): projection, simplification,
// smoothing, refinement through the map, and writing and reading a map file each call it, within
// a phase with `done` never decreasing and at most `total`, and end every phase they report with
// done == total; a callback that throws cancels the operation, the exception reaches the caller,
// and a map file being saved is left as it was.

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/construct/refine_through_map.hpp>
#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/progress.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace plmap {
namespace {

struct Call {
  std::string phase;
  std::uint64_t done, total;
};

/// Records every call; `check` asserts the rules above and returns the phases in order.
struct Recorder {
  std::vector<Call> calls;
  ProgressCallback callback() {
    return [this](const Progress& p) { calls.push_back({std::string(p.phase), p.done, p.total}); };
  }
  std::vector<std::string> check() const {
    std::vector<std::string> phases;
    std::map<std::string, Call> last;
    for (const Call& c : calls) {
      if (phases.empty() || phases.back() != c.phase) phases.push_back(c.phase);
      if (c.total > 0) {
        EXPECT_LE(c.done, c.total) << c.phase;
      }
      if (auto it = last.find(c.phase); it != last.end()) {
        EXPECT_GE(c.done, it->second.done) << c.phase << ": done went down";
        // a total once known stays; an unknown one (0) becomes known when the phase ends
        if (it->second.total != 0) {
          EXPECT_EQ(c.total, it->second.total) << c.phase << ": total changed";
        }
      }
      last[c.phase] = c;
    }
    for (const auto& [phase, c] : last) EXPECT_EQ(c.done, c.total) << phase << " did not end complete";
    return phases;
  }
};

const PlMap<2>& simplified_sphere() {
  static const PlMap<2> map = [] {
    generators::Rng rng(7);
    auto fine = std::make_shared<const Surface<2>>(generators::icosphere({3, 0.0}, rng));
    SimplifyOptions options;
    options.target_elements = 60;
    return simplify(fine, options).map;
  }();
  return map;
}

TEST(ProgressReports, Projection) {
  // enough S2 edges (> 4096) for more than one call inside the edge phase
  auto s1 = test::grid(40, 40, 0, 1, 0, 1, 0.0);
  auto s2 = test::grid(50, 50, 0, 1, 0, 1, 0.1);
  ASSERT_GT(s2->edge_count(), 4096);
  Recorder r;
  ProjectionOptions options;
  options.progress = r.callback();
  (void)project<2>(s1, s2, options);
  const auto phases = r.check();
  EXPECT_EQ(phases, (std::vector<std::string>{"rays from S1 vertices", "S2 vertex preimages", "S2 edges", "finalize"}));
  std::size_t edge_calls = 0;
  for (const Call& c : r.calls) edge_calls += c.phase == "S2 edges";
  EXPECT_GE(edge_calls, 3u);  // start, one block, the last block
}

TEST(ProgressReports, SimplificationTowardsAnElementTarget) {
  generators::Rng rng(3);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({3, 0.0}, rng));
  Recorder r;
  SimplifyOptions options;
  options.target_elements = 100;
  options.progress_every = 10;
  options.progress = r.callback();
  const SimplifyResult result = simplify(fine, options);
  EXPECT_EQ(r.check(), (std::vector<std::string>{"removing vertices", "finalize"}));
  ASSERT_GE(r.calls.size(), 4u);
  EXPECT_EQ(r.calls.front().total, static_cast<std::uint64_t>(fine->element_count() - 100));
  EXPECT_GT(result.report.removed_vertices, 0);
}

TEST(ProgressReports, SimplificationWithOnlyAnErrorBoundCountsRemovals) {
  generators::Rng rng(3);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({2, 0.0}, rng));
  Recorder r;
  SimplifyOptions options;
  options.max_error = 0.05;
  options.progress_every = 5;
  options.progress = r.callback();
  const SimplifyResult result = simplify(fine, options);
  r.check();
  const Call* last_removal = nullptr;
  for (const Call& c : r.calls)
    if (c.phase == "removing vertices") last_removal = &c;
  ASSERT_NE(last_removal, nullptr);
  EXPECT_EQ(last_removal->done, static_cast<std::uint64_t>(result.report.removed_vertices));
}

TEST(ProgressReports, SmoothingCountsSweeps) {
  Recorder r;
  SmoothOptions options;
  options.sweeps = 3;
  options.progress = r.callback();
  (void)smooth(simplified_sphere(), options);
  EXPECT_EQ(r.check(), std::vector<std::string>{"smoothing sweeps"});
  ASSERT_EQ(r.calls.size(), 6u);
  EXPECT_EQ(r.calls.back().done, 3u);
}

TEST(ProgressReports, RefinementThroughTheMap) {
  Recorder r;
  RefineOptions options;
  options.levels = 4;  // 60 * 256 refined triangles: several calls in "distance to S2"
  options.progress = r.callback();
  (void)refine_through_map(simplified_sphere(), options);
  EXPECT_EQ(r.check(), (std::vector<std::string>{"refining S1 elements", "distance to S2"}));
  EXPECT_GE(r.calls.size(), 5u);
}

TEST(ProgressReports, WritingAndReadingAMapFile) {
  auto s1 = test::grid(60, 60, 0, 1, 0, 1, 0.0);
  auto s2 = test::grid(70, 70, 0, 1, 0, 1, 0.1);
  const PlMap<2> map = project<2>(s1, s2).map;
  Recorder written;
  std::ostringstream out;
  write_map(out, map, written.callback());
  EXPECT_EQ(written.check(), std::vector<std::string>{"writing map"});
  EXPECT_GE(written.calls.size(), 2u);  // the text is several megabytes: flushed more than once

  Recorder read;
  const std::string text = out.str();
  (void)parse_map(text, "memory", MapReadOptions{.progress = read.callback()});
  EXPECT_EQ(read.check(), std::vector<std::string>{"reading map"});
  EXPECT_GE(read.calls.size(), 2u);
  EXPECT_EQ(read.calls.back().total, text.size());
}

TEST(ProgressReports, AThrowingCallbackCancelsAndLeavesTheFileAsItWas) {
  auto s1 = test::grid(60, 60, 0, 1, 0, 1, 0.0);
  auto s2 = test::grid(70, 70, 0, 1, 0, 1, 0.1);
  const PlMap<2> map = project<2>(s1, s2).map;
  const auto path = std::filesystem::temp_directory_path() / "plmap_progress_cancel.plmap";
  { std::ofstream(path) << "old content\n"; }
  int calls = 0;
  const ProgressCallback cancel = [&calls](const Progress&) {
    if (++calls == 2) throw std::runtime_error("cancelled");
  };
  EXPECT_THROW(save_map(path, map, cancel), std::runtime_error);
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "old content\n");
  std::filesystem::remove(path);

  ProjectionOptions options;
  options.progress = [](const Progress& p) {
    if (p.phase == "S2 edges") throw std::runtime_error("cancelled in the edges");
  };
  EXPECT_THROW((void)project<2>(s1, s2, options), std::runtime_error);
}

}  // namespace
}  // namespace plmap
