#pragma once
/// \file
/// VerificationReport: what the invariant checks found, violation by violation.
///
/// Violations are grouped by check (the sections of DESIGN.md §4: "structure", "plane_graph",
/// "minimal_embedding", "map", "continuity", "coverage", "quality") and, within a check, by rule
/// (e.g. "structure"/"ccw_order"). Each names the S1 element, node or region (or the S2 element
/// for coverage) and carries a message with the offending numbers.

#include <plmap/core/types.hpp>
#include <plmap/verify/quality.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace plmap {

namespace check_names {
inline constexpr std::string_view structure = "structure";
inline constexpr std::string_view plane_graph = "plane_graph";
inline constexpr std::string_view minimal_embedding = "minimal_embedding";
inline constexpr std::string_view map = "map";
inline constexpr std::string_view continuity = "continuity";
inline constexpr std::string_view coverage = "coverage";
inline constexpr std::string_view quality = "quality";
}  // namespace check_names

struct Violation {
  std::string check;  ///< one of check_names
  std::string rule;   ///< the specific invariant inside the check
  Index element = invalid_index;         ///< S1 element concerned, if any
  Index node = invalid_index;            ///< node concerned, if any
  Index region = invalid_index;          ///< region concerned, if any
  Index target_element = invalid_index;  ///< S2 element concerned, if any
  std::string message;                   ///< what is wrong, with the numbers
};

/// The outcome of one check.
struct CheckResult {
  std::string name;
  /// A check is skipped when the arrays it would read are not index-consistent (then the
  /// "structure" check reports why).
  bool skipped = false;
  std::string skipped_reason;
  /// All violations found, including those not stored in `violations`.
  std::size_t violation_count = 0;
  /// Per rule: number of violations found.
  std::map<std::string, std::size_t> rule_counts;
  /// The first VerifyOptions::max_reported_per_rule violations of each rule.
  std::vector<Violation> violations;

  bool ok() const { return violation_count == 0 && !skipped; }
};

struct VerificationReport {
  /// The checks that ran, in the order of DESIGN.md §4.
  std::vector<CheckResult> checks;
  /// Kappa statistics, when computed.
  std::optional<QualityReport> quality;

  /// True if every check ran and found nothing.
  bool ok() const;
  std::size_t violation_count() const;
  /// Violations of one check (0 if it did not run).
  std::size_t violation_count(std::string_view check) const;
  /// Violations of one rule of one check.
  std::size_t violation_count(std::string_view check, std::string_view rule) const;
  const CheckResult* find(std::string_view check) const;
  /// Appends the checks of another report (used to combine single checks).
  void merge(VerificationReport other);
};

/// A few human-readable lines: one per check, the counts per rule, the first violations and the
/// quality summary. The library never prints; callers decide where this goes.
std::string summary(const VerificationReport& report, std::size_t violations_per_check = 5);

}  // namespace plmap
