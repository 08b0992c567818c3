#pragma once
// What plmap::verify finds wrong with a map, as text for a test's failure message: shared by the
// core and construct tests (EXPECT_EQ(verify_violations(map), "")).

#include <plmap/core/pl_map.hpp>
#include <plmap/verify/check.hpp>

#include <sstream>
#include <string>

namespace plmap::test {

/// Every violation of every check of plmap::verify, one a line; empty when the map is valid.
template <int d>
std::string verify_violations(const PlMap<d>& map) {
  const VerificationReport report = verify(map);
  if (report.ok()) return {};
  std::ostringstream why;
  for (const auto& check : report.checks)
    for (const auto& v : check.violations)
      why << check.name << "/" << v.rule << " element " << v.element << ": " << v.message << "\n";
  return why.str().empty() ? std::string("verify failed without a listed violation") : why.str();
}

}  // namespace plmap::test
