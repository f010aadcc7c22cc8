#include "engine/telemetry/traffic_json.h"

namespace hitl::telemetry {

nlohmann::json to_json(const TrafficSummary& s) {
  nlohmann::json j;
  j["duration_s"] = s.duration_s;
  j["frames"] = s.frames;
  j["datagrams"] = s.datagrams;
  j["bytes"] = s.parser.bytes;
  j["crc_errors"] = s.parser.crc_errors;
  j["parse_errors"] = s.parser.parse_errors;
  j["garbage_bytes"] = s.parser.garbage_bytes;
  j["truncated"] = s.parser.truncated;
  j["segments"] = s.segments;
  j["set_aside_records"] = s.set_aside_records;
  j["unknown"] = s.parser.unknown_ids;
  j["unverified"] = s.parser.unverified;
  j["untracked_id_frames"] = s.untracked_id_frames;
  j["untracked_source_frames"] = s.untracked_source_frames;
  j["bad_incompat_flags"] = s.parser.bad_incompat_flags;
  j["signature_errors"] = s.parser.signature_errors;
  j["unsigned_rejected"] = s.parser.unsigned_rejected;
  j["v1_frames"] = s.parser.v1_frames;
  j["signed_frames"] = s.parser.signed_frames;
  nlohmann::json messages = nlohmann::json::object();
  for (const auto& m : s.messages) {
    messages[m.name] = {
        {"id", m.id},
        {"count", m.count},
        {"rate_hz", m.rate_hz},
        {"recent_rate_hz", m.recent_rate_hz},
        {"gap_us",
         {{"mean", m.gap.mean_us}, {"std", m.gap.std_us}, {"min", m.gap.min_us}, {"max", m.gap.max_us}, {"p50", m.gap.p50_us}, {"p99", m.gap.p99_us}}},
        {"bytes", m.bytes},
        {"bytes_per_s", m.bytes_per_s}};
  }
  j["messages"] = std::move(messages);
  nlohmann::json sources = nlohmann::json::array();
  for (const auto& src : s.sources) {
    sources.push_back({{"address", src.address},
                       {"sysid", src.sysid},
                       {"compid", src.compid},
                       {"received", src.seq.received},
                       {"lost", src.seq.lost},
                       {"out_of_order", src.seq.out_of_order},
                       {"loss_pct", 100.0 * src.seq.loss_ratio()}});
  }
  j["sources"] = std::move(sources);
  return j;
}

}  // namespace hitl::telemetry
