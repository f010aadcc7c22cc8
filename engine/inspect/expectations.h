// `--expect NAME=HZ[,NAME=HZ]`: rates a link must carry, and the verdict on a measurement.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/message_set.h"
#include "engine/telemetry/traffic_stats.h"

namespace hitl::inspect {

struct Expectation {
  std::string name;  ///< message name as the message set spells it
  uint32_t id = 0;
  double rate_hz = 0;
};

struct ExpectationResult {
  Expectation expected;
  double measured_hz = 0;
  double low_hz = 0;   ///< accepted range, from the tolerance
  double high_hz = 0;
  bool ok = false;
  std::string verdict;  ///< "ODOMETRY 249.8 Hz (expected 250 Hz ±5%): ok"
};

/// Parses "ODOMETRY=250,HIL_SENSOR=250"; names are checked against `messages` (any case, or ids).
Expected<std::vector<Expectation>> parse_expectations(std::string_view spec, const mavlink::MessageSet& messages);

/// A log with more than this share of its records set aside (stamps that jumped) is not judged.
inline constexpr double kMaxSetAsidePct = 1.0;

/// Judges each expectation against the measured rate_hz, within ±tolerance_pct percent. Nothing
/// passes on a log it cannot measure honestly: more than kMaxSetAsidePct of its records set aside.
std::vector<ExpectationResult> check_expectations(const telemetry::TrafficSummary& summary,
                                                  const std::vector<Expectation>& expectations, double tolerance_pct);

}  // namespace hitl::inspect
