// Human renderings of a TrafficSummary: the full table and the one-line status.
#pragma once

#include <string>

#include "engine/telemetry/traffic_stats.h"

namespace hitl::cli {

/// Per message: id, count, rate, gap mean/std/max, bytes/s; per source: loss; then error counters.
std::string traffic_table(const telemetry::TrafficSummary& summary);
/// "12.0 s  3000 frames  HIL_SENSOR 250.0 Hz  ODOMETRY 250.1 Hz  crc 0  parse 0  unknown 0"
std::string traffic_line(const telemetry::TrafficSummary& summary);

}  // namespace hitl::cli
