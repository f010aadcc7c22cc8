#include "tui/inspect_dashboard.h"

#include <algorithm>
#include <cstring>

#include "base/common/clock.h"
#include "base/mavlink/messages.h"
#include "tui/draw.h"

namespace hitl::tui {

InspectDashboard::InspectDashboard(std::string where, std::map<std::string, double> expected_hz, bool stay_open)
    : where_(std::move(where)), expected_hz_(std::move(expected_hz)), stay_open_(stay_open) {}

void InspectDashboard::on_frame(const mavlink::Frame& frame, const std::string& source, int64_t) {
  if (!frame.is<mavlink::msg::Statustext>() || frame.desc == nullptr) return;
  source_of_sysid_[frame.sysid] = source;
  for (const auto& text : statustexts_.on_frame(frame, monotonic_s())) show(text);
}

void InspectDashboard::show(const mavlink::StatusText& text) {
  const std::string from = source_of_sysid_[text.sysid] + " " + std::to_string(text.sysid);
  log_.add_statustext(severity_from_mavlink(text.severity), from, "[" + from + "] " + text.text);  // the log cleans it
}

void InspectDashboard::on_tick(const telemetry::TrafficSummary& summary) {
  for (const auto& text : statustexts_.expire(monotonic_s())) show(text);
  std::lock_guard<std::mutex> lock(mutex_);
  summary_ = summary;
}

void InspectDashboard::mark_finished(const std::string& why) {
  log_.add(Severity::Notice, "inspect ended: " + why + (stay_open_ ? " (q quits)" : ""));
  std::lock_guard<std::mutex> lock(mutex_);
  finished_ = why;
}

std::optional<std::string> InspectDashboard::finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  return stay_open_ ? std::nullopt : finished_;
}

DashboardModel InspectDashboard::collect() {
  DashboardModel m;
  m.title = "hitl inspect";
  std::optional<telemetry::TrafficSummary> s;
  std::optional<std::string> ended;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s = summary_;
    ended = finished_;
  }
  m.state = ended ? "ended: " + *ended : (s && s->frames > 0 ? "receiving" : "waiting for frames");
  m.state_health = ended || (s && s->frames > 0) ? Health::Good : Health::Degraded;
  m.clock = format("%.1f s", s ? s->duration_s : 0.0);
  m.link_partner = where_;
  m.messages = log_.lines();
  m.outcome = log_.outcome();
  m.paths.caption = expected_hz_.empty() ? "rates over the last second; --expect NAME=HZ sets what they should be"
                                         : "held to --expect; jitter and max gap since the start";
  if (!s) return m;
  for (const auto& msg : s->messages) {
    PathRow row;
    row.name = msg.name;
    row.message = msg.name;
    row.outgoing = false;
    const auto e = expected_hz_.find(msg.name);
    row.expected_hz = e == expected_hz_.end() ? 0.0 : e->second;
    row.rate_hz = msg.recent_rate_hz;
    row.jitter_ms = msg.gap.std_us / 1000.0;
    row.max_gap_ms = msg.gap.max_us / 1000.0;
    row.count = msg.count;
    const bool stale = !ended && msg.recent_rate_hz <= 0;
    row.health = telemetry::rate_health(row.expected_hz, row.rate_hz, stale && row.expected_hz > 0);
    if (stale && row.expected_hz <= 0) row.note = "quiet";
    m.paths.rows.push_back(std::move(row));
  }
  for (const auto& [name, hz] : expected_hz_) {  // expected but never seen: a red row
    bool seen = false;
    for (const auto& r : m.paths.rows) seen = seen || r.name == name;
    if (seen) continue;
    PathRow row;
    row.name = name;
    row.message = name;
    row.outgoing = false;
    row.expected_hz = hz;
    row.health = Health::Bad;
    m.paths.rows.push_back(std::move(row));
  }
  // What fails its --expect first, so a busy link's forty messages do not push it off the panel.
  std::stable_partition(m.paths.rows.begin(), m.paths.rows.end(),
                        [](const PathRow& r) { return r.expected_hz > 0 && r.health != Health::Good; });
  auto count = [](uint64_t n) { return std::to_string(n); };
  const auto& p = s->parser;
  m.link = {{"frames", count(s->frames)},
            {"datagrams", count(s->datagrams)},
            {"crc err", count(p.crc_errors), p.crc_errors > 0 ? Health::Degraded : Health::Good},
            {"parse err", count(p.parse_errors), p.parse_errors > 0 ? Health::Degraded : Health::Good},
            {"sources", count(s->sources.size())}};
  for (const auto& src : s->sources) {
    const double loss_pct = src.seq.loss_ratio() * 100.0;
    m.link.push_back({format("%u/%u lost", static_cast<unsigned>(src.sysid), static_cast<unsigned>(src.compid)),
                      count(src.seq.lost) + format(" (%.1f%%)", loss_pct), src.seq.lost > 0 ? Health::Degraded : Health::Good});
  }
  return m;
}

}  // namespace hitl::tui
