#include "engine/telemetry/health.h"

#include <cmath>

namespace hitl::telemetry {

Health rate_health(double expected_hz, double measured_hz, bool stale) {
  if (stale || !std::isfinite(measured_hz)) return Health::Bad;
  if (!(expected_hz > 0) || !std::isfinite(expected_hz)) return Health::Good;  // nothing to hold it to
  const double off_pct = std::fabs(measured_hz - expected_hz) / expected_hz * 100.0;
  if (off_pct <= kGoodWithin_pct) return Health::Good;
  if (off_pct <= kDegradedWithin_pct) return Health::Degraded;
  return Health::Bad;
}

const char* to_string(Health health) {
  switch (health) {
    case Health::Good: return "ok";
    case Health::Degraded: return "warn";
    case Health::Bad: return "bad";
  }
  return "?";
}

}  // namespace hitl::telemetry
