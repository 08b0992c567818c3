// projection_report_json (construct/projection_report_json.hpp): the one JSON form of the report
// that `plmap project --json` and Python's Map.report print. Its values against the report they
// come from, and the list of missing edges cut at the limit while their number stays whole.
#include "projection_fixtures.hpp"
#include "rim_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/construct/projection_report_json.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace plmap;
using namespace plmap::test;

namespace {

/// A pair with edges not inserted: the flat square under a tilted plane, with a distance limit
/// that the plane crosses (the walks stop there).
ProjectionResult<2> tilted_pair_with_limit() {
  return project<2>(flat_square(), tilted_plane(0.3), with_limit(0.1));
}

}  // namespace

TEST(ProjectionReportJson, ValuesAreTheReportsAndTheListStopsAtTheLimit) {
  const ProjectionResult<2> r = tilted_pair_with_limit();
  const std::size_t missing = r.report.edges_not_inserted.size();
  ASSERT_GE(missing, 3u);  // else the cut below tests nothing
  const auto j = projection_report_json(r, 2);
  EXPECT_EQ(j.at("dimension").get<int>(), 2);
  EXPECT_EQ(j.at("covered_measure").get<double>(), r.measures.covered_domain);
  EXPECT_EQ(j.at("domain_measure").get<double>(), r.measures.domain);
  EXPECT_EQ(j.at("regions").get<Index>(), r.map.region_count());
  EXPECT_EQ(j.at("edges_inserted").get<Index>(), r.report.edges_inserted);
  EXPECT_EQ(j.at("rim_nodes").get<Index>(), r.report.rim_nodes);
  EXPECT_EQ(j.at("rim_edges").get<Index>(), r.report.rim_edges);
  // the number counts every missing edge; the list holds the first two, in the report's order
  EXPECT_EQ(j.at("edges_not_inserted").get<std::size_t>(), missing);
  const auto& listed = j.at("edges_not_inserted_list");
  ASSERT_EQ(listed.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const EdgeNotInserted<2>& e = r.report.edges_not_inserted[i];
    EXPECT_EQ(listed[i].at("target_edge").get<Index>(), e.target_edge);
    EXPECT_EQ(listed[i].at("reason").get<std::string>(), std::string(to_string(e.reason)));
    EXPECT_EQ(listed[i].at("domain_point").get<std::vector<double>>(),
              (std::vector<double>{e.domain_point.x(), e.domain_point.y(), e.domain_point.z()}));
  }
  // the default lists them all
  EXPECT_EQ(projection_report_json(r).at("edges_not_inserted_list").size(), missing);
  // S1's measure, split into what D covers and what it leaves out by why
  double sum = j.at("covered_measure").get<double>();
  for (const auto& [name, measure] : r.report.left_out.fields()) {
    EXPECT_EQ(j.at("left_out_measure").at(name).get<double>(), r.report.left_out.*measure) << name;
    sum += j.at("left_out_measure").at(name).get<double>();
  }
  EXPECT_NEAR(sum, r.measures.domain, 1e-12);
  EXPECT_EQ(j.at("seconds").get<double>(), r.report.seconds.total);
  EXPECT_EQ(j.at("seconds_by_phase").at("finalize").get<double>(), r.report.seconds.finalize);
  EXPECT_EQ(j.at("renumbered").at("S1").get<bool>(), r.report.renumbered_domain);
  EXPECT_EQ(j.at("renumbered").at("S2").get<bool>(), r.report.renumbered_target);
}

TEST(ProjectionReportJson, CurvesHaveNoLeftOutMeasuresAndTwoCoordinatesPerPoint) {
  // a segment under a tilted segment that leaves the distance limit: missing edges with points
  // in the plane
  ProjectionOptions rules;
  rules.max_distance = 0.1;
  std::vector<WorldPoint<1>> v{{-0.1, 0.05}, {0.3, 0.09}, {0.7, 0.13}, {1.1, 0.17}};
  std::vector<ElementCorners<1>> e{{0, 1}, {1, 2}, {2, 3}};
  const auto s2 = std::make_shared<const Surface<1>>(std::move(v), std::move(e));
  const ProjectionResult<1> r = project<1>(line(4, 0.0, 1.0, 0.0), s2, rules);
  ASSERT_FALSE(r.report.edges_not_inserted.empty());
  const auto j = projection_report_json(r);
  EXPECT_EQ(j.at("dimension").get<int>(), 1);
  EXPECT_FALSE(j.contains("left_out_measure"));
  EXPECT_EQ(j.at("edges_not_inserted_list").at(0).at("domain_point").size(), 2u);
}
