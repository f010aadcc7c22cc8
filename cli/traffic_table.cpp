#include "cli/traffic_table.h"

#include <cstdio>

namespace hitl::cli {
namespace {

std::string fmt(const char* format, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

}  // namespace

std::string traffic_table(const telemetry::TrafficSummary& s) {
  std::string out = fmt("%-28s %7s %9s %9s %9s %9s %9s %9s\n", "MESSAGE", "ID", "COUNT", "RATE Hz", "GAP us", "STD us",
                        "MAX us", "BYTES/s");
  for (const auto& m : s.messages)
    out += fmt("%-28s %7u %9llu %9.1f %9.0f %9.0f %9.0f %9.0f\n", m.name.c_str(), m.id,
               static_cast<unsigned long long>(m.count), m.rate_hz, m.gap.mean_us, m.gap.std_us, m.gap.max_us,
               m.bytes_per_s);
  if (s.messages.empty()) out += "(no MAVLink frames yet)\n";
  if (!s.sources.empty()) {
    out += fmt("\n%-28s %7s %9s %9s %9s %9s\n", "SOURCE", "SYSID", "COMPID", "RECEIVED", "LOST", "LOSS %");
    for (const auto& src : s.sources)
      out += fmt("%-28s %7u %9u %9llu %9llu %9.2f\n", src.address.c_str(), src.sysid, src.compid,
                 static_cast<unsigned long long>(src.seq.received), static_cast<unsigned long long>(src.seq.lost),
                 100.0 * src.seq.loss_ratio());
  }
  out += fmt("\n%.1f s  %llu frames in %llu datagrams  crc errors %llu  parse errors %llu  unverified %llu  truncated %llu",
             s.duration_s, static_cast<unsigned long long>(s.frames), static_cast<unsigned long long>(s.datagrams),
             static_cast<unsigned long long>(s.parser.crc_errors), static_cast<unsigned long long>(s.parser.parse_errors),
             static_cast<unsigned long long>(s.parser.unverified), static_cast<unsigned long long>(s.parser.truncated));
  if (s.parser.signature_errors + s.parser.unsigned_rejected + s.parser.bad_incompat_flags > 0)
    out += fmt("  signature errors %llu  unsigned rejected %llu  bad incompat flags %llu",
               static_cast<unsigned long long>(s.parser.signature_errors),
               static_cast<unsigned long long>(s.parser.unsigned_rejected),
               static_cast<unsigned long long>(s.parser.bad_incompat_flags));
  out += "\n";
  if (s.segments > 1 || s.set_aside_records > 0)
    out += fmt("log time: %llu segment%s%s, %llu record%s set aside (a stamp that jumped and no next record confirmed)\n",
               static_cast<unsigned long long>(s.segments), s.segments == 1 ? "" : "s",
               s.segments == 1 ? "" : " measured apart (the log's clock jumped back, or ahead more than 60 s)",
               static_cast<unsigned long long>(s.set_aside_records), s.set_aside_records == 1 ? "" : "s");
  return out;
}

std::string traffic_line(const telemetry::TrafficSummary& s) {
  std::string out = fmt("%.1f s  %llu frames", s.duration_s, static_cast<unsigned long long>(s.frames));
  for (const auto& m : s.messages) out += fmt("  %s %.1f Hz", m.name.c_str(), m.recent_rate_hz);
  out += fmt("  crc %llu  parse %llu  unverified %llu", static_cast<unsigned long long>(s.parser.crc_errors),
             static_cast<unsigned long long>(s.parser.parse_errors), static_cast<unsigned long long>(s.parser.unverified));
  return out;
}

}  // namespace hitl::cli
