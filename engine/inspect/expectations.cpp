#include "engine/inspect/expectations.h"

#include <cmath>
#include <cstdio>

namespace hitl::inspect {
namespace {

std::string trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return std::string(s);
}

}  // namespace

Expected<std::vector<Expectation>> parse_expectations(std::string_view spec, const mavlink::MessageSet& messages) {
  std::vector<Expectation> out;
  while (!spec.empty()) {
    const auto comma = spec.find(',');
    const std::string item = trim(spec.substr(0, comma));
    spec = comma == std::string_view::npos ? std::string_view{} : spec.substr(comma + 1);
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos) return Error::input("'" + item + "' is not NAME=HZ");
    const std::string name = trim(std::string_view(item).substr(0, eq));
    const std::string hz = trim(std::string_view(item).substr(eq + 1));
    const auto* desc = messages.lookup(name);
    if (desc == nullptr) return Error::input("unknown message '" + name + "' (load its dialect with --dialect FILE.xml)");
    char* end = nullptr;
    const double rate = std::strtod(hz.c_str(), &end);
    if (hz.empty() || end != hz.c_str() + hz.size() || !std::isfinite(rate) || rate <= 0)
      return Error::input("rate '" + hz + "' for " + desc->name + " is not a positive number of Hz");
    out.push_back(Expectation{desc->name, desc->id, rate});
  }
  if (out.empty()) return Error::input("no NAME=HZ given");
  return out;
}

std::vector<ExpectationResult> check_expectations(const telemetry::TrafficSummary& summary,
                                                  const std::vector<Expectation>& expectations, double tolerance_pct) {
  std::vector<ExpectationResult> results;
  const double records = static_cast<double>(summary.datagrams + summary.set_aside_records);
  const double set_aside_pct = records > 0 ? 100.0 * static_cast<double>(summary.set_aside_records) / records : 0.0;
  for (const auto& e : expectations) {
    ExpectationResult r;
    r.expected = e;
    r.low_hz = e.rate_hz * (1.0 - tolerance_pct / 100.0);
    r.high_hz = e.rate_hz * (1.0 + tolerance_pct / 100.0);
    uint64_t count = 0;
    for (const auto& m : summary.messages)
      if (m.id == e.id) {
        r.measured_hz = m.rate_hz;
        count = m.count;
      }
    r.ok = count >= 2 && r.measured_hz >= r.low_hz && r.measured_hz <= r.high_hz && set_aside_pct <= kMaxSetAsidePct;
    char buf[320];
    if (set_aside_pct > kMaxSetAsidePct) {
      std::snprintf(buf, sizeof buf, "%s: not judged: %llu of %.0f records (%.1f%%) set aside for stamps that jump, more than %g%% (measured %.1f Hz)",
                    e.name.c_str(), static_cast<unsigned long long>(summary.set_aside_records), records, set_aside_pct,
                    kMaxSetAsidePct, r.measured_hz);
    } else if (count == 0) {
      std::snprintf(buf, sizeof buf, "%s: none received (expected %g Hz)", e.name.c_str(), e.rate_hz);
    } else if (count < 2) {
      std::snprintf(buf, sizeof buf, "%s: only 1 received (expected %g Hz)", e.name.c_str(), e.rate_hz);
    } else {
      std::snprintf(buf, sizeof buf, "%s: %.1f Hz (expected %g Hz ±%g%%: %.1f..%.1f): %s", e.name.c_str(), r.measured_hz,
                    e.rate_hz, tolerance_pct, r.low_hz, r.high_hz,
                    r.ok ? "ok" : (r.measured_hz < r.low_hz ? "too slow" : "too fast"));
    }
    r.verdict = buf;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace hitl::inspect
