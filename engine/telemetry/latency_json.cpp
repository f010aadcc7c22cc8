#include "engine/telemetry/latency_json.h"

namespace hitl::telemetry {

nlohmann::json to_json(const LatencySummary& s, bool with_histogram) {
  nlohmann::json j = {{"count", s.count}, {"min_us", s.min_us}, {"mean_us", s.mean_us}, {"p50_us", s.p50_us},
                      {"p95_us", s.p95_us}, {"p99_us", s.p99_us}, {"max_us", s.max_us}};
  if (!with_histogram) return j;
  nlohmann::json bins = nlohmann::json::array();
  for (const auto& b : s.bins)
    bins.push_back({{"lo_us", b.lo_us}, {"hi_us", b.hi_us ? nlohmann::json(b.hi_us) : nlohmann::json(nullptr)}, {"count", b.count}});
  j["histogram"] = std::move(bins);
  return j;
}

}  // namespace hitl::telemetry
