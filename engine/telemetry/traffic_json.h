// The JSON form of a TrafficSummary: field names are a contract with users' scripts
// (`hitl inspect --json`, and the per-message tables of later commands).
#pragma once

#include <nlohmann/json.hpp>

#include "engine/telemetry/traffic_stats.h"

namespace hitl::telemetry {

/// {duration_s, frames, datagrams, crc_errors, parse_errors, unknown, truncated, ...,
///  messages: {NAME: {id, count, rate_hz, recent_rate_hz, gap_us: {mean, std, min, max, p50, p99}, bytes, bytes_per_s}},
///  sources: [{address, sysid, compid, received, lost, out_of_order, loss_pct}]}
nlohmann::json to_json(const TrafficSummary& summary);

}  // namespace hitl::telemetry
