// The JSON form of a LatencySummary: field names are a contract with users' scripts
// (`hitl sim --json`'s "loop_latency", docs/sim.md).
#pragma once

#include <nlohmann/json.hpp>

#include "engine/telemetry/latency_histogram.h"

namespace hitl::telemetry {

/// {count, min_us, mean_us, p50_us, p95_us, p99_us, max_us}, and with `with_histogram`
/// "histogram": [{lo_us, hi_us (null: no upper edge), count}, ...] over kLatencyBinEdges_us.
nlohmann::json to_json(const LatencySummary& summary, bool with_histogram);

}  // namespace hitl::telemetry
