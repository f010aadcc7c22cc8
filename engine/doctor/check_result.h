// One `hitl doctor` check's outcome: pass / warn / fail / skip, what it saw, and the command that
// fixes it. Verdicts are ordered by severity (drake's KeepMoreSevere): the worst decides the exit.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace hitl::doctor {

enum class Verdict { Pass, Skip, Warn, Fail };

/// "pass", "skip", "warn", "fail" (the JSON's `result`).
const char* to_string(Verdict verdict);
constexpr Verdict worse(Verdict a, Verdict b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

struct CheckResult {
  std::string check;   ///< the check's id, e.g. "heartbeat" (check_catalog.h)
  std::string group;   ///< "host", "link", "board sensors", ...
  Verdict result = Verdict::Skip;
  std::string saw;     ///< what it saw; for a skip, why it was skipped
  std::string fix;     ///< the command that fixes it (warn and fail); empty otherwise
};

struct DoctorSummary {
  std::size_t passed = 0, warned = 0, failed = 0, skipped = 0;
  Verdict worst = Verdict::Pass;
  bool ok() const { return failed == 0; }  ///< exit 0 when nothing failed
};

DoctorSummary summarize(const std::vector<CheckResult>& results);

/// A figure for a check's "seen" text: `v` with `digits` decimals.
std::string fixed(double v, int digits);

}  // namespace hitl::doctor
