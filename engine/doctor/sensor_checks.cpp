#include "engine/doctor/sensor_checks.h"

#include <cmath>
#include <cstdio>

#include "base/contract/dsp_hitl_status.h"
#include "engine/doctor/check_catalog.h"

namespace hitl::doctor {
namespace {

std::optional<target::DspHitlStatusReport> parse(const DspHitlRead& r, std::string* why) {
  if (!r.text) {
    *why = r.text.error().message;
    return std::nullopt;
  }
  target::DspHitlStatusReport report;
  if (!target::parse_dsp_hitl_status(r.text.value(), &report, why)) return std::nullopt;
  return report;
}

bool not_found(const DspHitlRead& r) { return r.text && r.text.value().find("command not found") != std::string::npos; }

}  // namespace

bool dsp_hitl_counting(const DspHitlRead& first, const DspHitlRead& second) {
  std::string why;
  const auto a = parse(first, &why), b = parse(second, &why);
  return a && b && b->counters.hil_imu_received > a->counters.hil_imu_received;
}

CheckResult dsp_hitl_check(const DspHitlRead& first, const DspHitlRead& second, double pace,
                           std::optional<bool> simulator_sending) {
  const char* status_cmd = "hitl shell -c \"qshell dsp_hitl status\"";
  if (not_found(first) || not_found(second))
    return make_result(check::kDspHitl, Verdict::Skip,
                       "this flight stack has no dsp_hitl (not a VOXL2 HITL build: PX4 SITL has none)");
  std::string why;
  const auto a = parse(first, &why);
  const auto b = a ? parse(second, &why) : std::nullopt;
  if (!a || !b)
    return make_result(check::kDspHitl, Verdict::Fail, "qshell dsp_hitl status: " + why,
                       std::string("look at it yourself: ") + status_cmd);
  if (!b->running)
    return make_result(check::kDspHitl, Verdict::Fail, "dsp_hitl is not running",
                       "hitl shell -c \"qshell dsp_hitl start\", or restart PX4 HITL: adb shell voxl-px4-hitl start");
  telemetry::DspHitlMeter meter(telemetry::spec_dsp_hitl_expected_rates());
  meter.on_report(*a, first.t_s);
  meter.on_report(*b, second.t_s);
  const auto view = meter.view(second.t_s);
  const double dt_s = second.t_s - first.t_s;
  std::string rates;
  bool any_stalled = false, all_stalled = true;
  double worst_ratio = 1.0;  // furthest from 1, as a factor either way
  const char* worst_name = "";
  for (const auto& c : view.counters) {
    const bool stalled = c.stalled || !c.rate_hz;
    any_stalled = any_stalled || stalled;
    all_stalled = all_stalled && stalled;
    const double expected_hz = c.expected_hz * pace;
    rates += (rates.empty() ? "" : ", ") + std::string(c.name) + " " +
             (c.rate_hz ? fixed(*c.rate_hz, 0) : std::string("?")) + "/" + fixed(expected_hz, 0) + " Hz";
    if (c.rate_hz && expected_hz > 0 && *c.rate_hz > 0) {
      const double r = *c.rate_hz / expected_hz;
      const double off = r >= 1 ? r : 1 / r;
      if (off > worst_ratio) {
        worst_ratio = off;
        worst_name = c.name;
      }
    }
  }
  const std::string over = " over " + fixed(dt_s, 1) + " s (measured/expected: " + rates + ")";
  const std::string feed_fix = simulator_sending.value_or(false)
                                   ? "the simulator sends, but nothing reaches the DSP over MUORB: restart PX4 HITL (adb shell "
                                     "voxl-px4-hitl start); check hitl doctor's mavlink-instances and hil-mode"
                                   : "start the simulator (hitl sim -i BOARD_IP) and check it is not paused";
  if (all_stalled)
    return make_result(check::kDspHitl, Verdict::Fail,
                       "counters stopped: HIL sensor_imu received stays at " + std::to_string(b->counters.hil_imu_received) + over,
                       feed_fix);
  if (any_stalled)
    return make_result(check::kDspHitl, Verdict::Fail, "some counters stopped" + over,
                       "the simulator's mag/baro groups must be complete (fields_updated); " + feed_fix);
  if (worst_ratio > 2.0)
    return make_result(check::kDspHitl, Verdict::Fail, std::string(worst_name) + " far from the spec's rate" + over, feed_fix);
  if (worst_ratio > 1.25)
    return make_result(check::kDspHitl, Verdict::Warn, std::string(worst_name) + " off the spec's rate" + over,
                       "a loaded host or board; hitl doctor's real-time and late-ticks checks say which");
  return make_result(check::kDspHitl, Verdict::Pass, "running, counters increasing" + over);
}

}  // namespace hitl::doctor
