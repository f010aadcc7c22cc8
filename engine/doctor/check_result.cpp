#include "engine/doctor/check_result.h"

#include <cstdio>

namespace hitl::doctor {

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: return "pass";
    case Verdict::Skip: return "skip";
    case Verdict::Warn: return "warn";
    case Verdict::Fail: return "fail";
  }
  return "?";
}

DoctorSummary summarize(const std::vector<CheckResult>& results) {
  DoctorSummary s;
  for (const auto& r : results) {
    s.worst = worse(s.worst, r.result);
    switch (r.result) {
      case Verdict::Pass: ++s.passed; break;
      case Verdict::Skip: ++s.skipped; break;
      case Verdict::Warn: ++s.warned; break;
      case Verdict::Fail: ++s.failed; break;
    }
  }
  return s;
}

std::string fixed(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace hitl::doctor
