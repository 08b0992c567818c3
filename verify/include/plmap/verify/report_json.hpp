#pragma once
/// \file
/// JSON form of a VerificationReport, for CI artefacts and the command line's --json output.

#include <plmap/verify/report.hpp>

#include <nlohmann/json.hpp>

namespace plmap {

/// {"ok": bool, "violation_count": n, "checks": {name: {"skipped", "violation_count",
///  "rules": {rule: n}, "violations": [{...}]}}, "quality": {...}}
nlohmann::json to_json(const VerificationReport& report);
nlohmann::json to_json(const QualityReport& quality);

}  // namespace plmap
