#include "engine/doctor/estimator_checks.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/mavlink/enums.h"
#include "engine/doctor/check_catalog.h"
#include "engine/telemetry/estimator_flags.h"

namespace hitl::doctor {
namespace {

const char* kEkfLook = "hitl shell -c \"ekf2 status\" (PX4: listener estimator_status)";

}  // namespace

CheckResult estimator_check(const std::optional<EstimatorStatusSeen>& status) {
  if (!status) return make_result(check::kEstimator, Verdict::Skip, "no ESTIMATOR_STATUS from the board (asked for one)");
  namespace e = mavlink::estimator_status;
  const uint16_t required = e::kAttitude | e::kVelocityHoriz | e::kVelocityVert | e::kPosHorizAbs | e::kPosVertAbs;
  std::string missing, faults;
  // PX4 v1.16 sets CONST_POS_MODE whenever the vehicle is at rest, also while it fuses GNSS
  // (ekf_helper.cpp: fake_pos || valid_fake_pos || vehicle_at_rest): a fault only without an
  // absolute horizontal position.
  const bool absolute_position = (status->flags & e::kPosHorizAbs) != 0;
  for (const auto& f : telemetry::estimator_flags(status->flags)) {
    if ((required & f.bit) != 0 && !f.set) missing += (missing.empty() ? "" : ", ") + std::string(f.word);
    if (f.bit == e::kConstPosMode && absolute_position) continue;
    if (f.fault && f.set) faults += (faults.empty() ? "" : ", ") + std::string(f.word);
  }
  struct Ratio {
    const char* name;
    double value;
    bool sensor_optional;  ///< a sensor the x500 lacks: NaN is PX4 v1.16's "not fused"
  };
  const Ratio ratios[] = {{"velocity", status->vel_ratio, false},
                          {"horizontal position", status->pos_horiz_ratio, false},
                          {"height", status->pos_vert_ratio, false},
                          {"magnetometer", status->mag_ratio, false},
                          {"height above ground", status->hagl_ratio, true},
                          {"airspeed", status->tas_ratio, true}};
  std::string high, raised;
  for (const auto& r : ratios) {
    if (r.sensor_optional && std::isnan(r.value)) continue;
    if (!(r.value <= 1.0)) high += (high.empty() ? "" : ", ") + std::string(r.name) + " " + fixed(r.value, 2);
    else if (r.value > kTestRatioWarn) raised += (raised.empty() ? "" : ", ") + std::string(r.name) + " " + fixed(r.value, 2);
  }
  char flags[16];
  std::snprintf(flags, sizeof flags, "0x%04X", status->flags);
  const std::string ratios_text = "test ratios vel " + fixed(status->vel_ratio, 2) + " pos " + fixed(status->pos_horiz_ratio, 2) +
                                  " hgt " + fixed(status->pos_vert_ratio, 2) + " mag " + fixed(status->mag_ratio, 2);
  std::string problems;
  if (!missing.empty()) problems += "not converged (no " + missing + ")";
  if (!faults.empty()) problems += std::string(problems.empty() ? "" : "; ") + "fault flags: " + faults;
  if (!high.empty()) problems += std::string(problems.empty() ? "" : "; ") + "test ratios above 1 (measurements rejected): " + high;
  if (!problems.empty())
    return make_result(check::kEstimator, Verdict::Fail, problems + "; flags " + flags + ", " + ratios_text,
                       std::string("EKF2 rejects what it is given: check the dsp-hitl check's sensors and the GPS "
                                   "(hitl inspect --connect BOARD_IP:14558 --show GPS_RAW_INT), the EKF2 parameters, then ") +
                           kEkfLook);
  if (!raised.empty())
    return make_result(check::kEstimator, Verdict::Warn, "converged, but test ratios are high: " + raised + "; flags " + flags,
                       kEkfLook);
  return make_result(check::kEstimator, Verdict::Pass, std::string("converged, flags ") + flags + ", " + ratios_text);
}

std::vector<std::string> preflight_failures(const std::vector<std::string>& statustext, const std::string& commander_check) {
  std::vector<std::string> out;
  auto add = [&](std::string line) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    const auto at = line.find("Preflight Fail");
    if (at == std::string::npos) return;
    line = line.substr(at);
    for (const auto& o : out)
      if (o == line) return;
    out.push_back(line);
  };
  for (const auto& t : statustext) add(t);
  std::istringstream in(commander_check);
  std::string line;
  while (std::getline(in, line)) add(line);
  return out;
}

CheckResult arming_check(const std::optional<HeartbeatSeen>& heartbeat, const std::optional<SysStatusSeen>& sys_status,
                         const std::vector<std::string>& statustext, const Expected<std::string>& commander_check) {
  if (!heartbeat) return make_result(check::kArming, Verdict::Skip, "no HEARTBEAT from the board");
  if (heartbeat->armed()) return make_result(check::kArming, Verdict::Pass, "armed");
  namespace b = mavlink::sys_status;
  std::optional<bool> ready;
  std::string unhealthy;
  if (sys_status) {
    if ((sys_status->present & b::kPrearmCheck) != 0) ready = (sys_status->health & b::kPrearmCheck) != 0;
    struct Sensor {
      uint32_t bit;
      const char* word;
    };
    static constexpr Sensor kSensors[] = {{b::kGyro, "gyro"},   {b::kAccel, "accelerometer"}, {b::kMag, "magnetometer"},
                                          {b::kAbsolutePressure, "barometer"}, {b::kGps, "GPS"}, {b::kAhrs, "attitude estimate"}};
    for (const auto& s : kSensors)
      if ((sys_status->enabled & s.bit) != 0 && (sys_status->health & s.bit) == 0)
        unhealthy += (unhealthy.empty() ? "" : ", ") + std::string(s.word);
  }
  const std::string check_text = commander_check ? commander_check.value() : std::string();
  if (!ready && commander_check) {
    if (check_text.find("Preflight check: OK") != std::string::npos) ready = true;
    else if (check_text.find("FAILED") != std::string::npos || check_text.find("Preflight Fail") != std::string::npos) ready = false;
  }
  if (!ready)
    return make_result(check::kArming, Verdict::Skip,
                       "the board says nothing about its preflight checks (no SYS_STATUS prearm bit, commander check: " +
                           (commander_check ? "'" + check_text.substr(0, 80) + "'" : commander_check.error().message) + ")");
  if (*ready) return make_result(check::kArming, Verdict::Pass, "ready to arm (SYS_STATUS prearm check healthy)");
  const auto reasons = preflight_failures(statustext, check_text);
  std::string saw = "not ready to arm";
  for (const auto& r : reasons) saw += ": " + r;
  if (reasons.empty()) saw += " (the board gave no reason)";
  if (!unhealthy.empty()) saw += "; SYS_STATUS unhealthy: " + unhealthy;
  std::string fix = "hitl shell -c \"commander check\"";
  const std::string all = saw;
  if (all.find("uncalibrated") != std::string::npos)
    fix = "the CAL_*_ID parameters must be dsp_hitl's device IDs (hitl doctor's params-calibration): hitl params reset, then "
          "restart PX4: adb shell voxl-px4-hitl start";
  else if (all.find("missing") != std::string::npos)
    fix = "sensor data does not reach the flight stack: see the dsp-hitl check";
  else if (all.find("estimate") != std::string::npos || all.find("ekf2") != std::string::npos || all.find("GPS") != std::string::npos)
    fix = "EKF2 has not converged: see the estimator check, then " + std::string(kEkfLook);
  return make_result(check::kArming, Verdict::Fail, saw, fix);
}

}  // namespace hitl::doctor
