#include "engine/doctor/check_catalog.h"

#include <stdexcept>

namespace hitl::doctor {

const std::vector<CheckInfo>& doctor_checks() {
  static const std::vector<CheckInfo> checks = {
      {check::kRoute, group::kHost, "route to the board"},
      {check::kAdb, group::kHost, "adb devices"},
      {check::kPorts, group::kHost, "HIL and VIO ports on this host"},
      {check::kHeartbeat, group::kLink, "HEARTBEAT from the board"},
      {check::kHilMode, group::kLink, "PX4 in HIL mode"},
      {check::kMavlinkInstances, group::kLink, "MAVLink instances (mavlink status)"},
      {check::kActuators, group::kLink, "HIL_ACTUATOR_CONTROLS rate"},
      {check::kActuatorFlags, group::kLink, "HIL_ACTUATOR_CONTROLS flags"},
      {check::kArmedState, group::kLink, "armed bit agrees with HEARTBEAT"},
      {check::kDspHitl, group::kSensors, "dsp_hitl counters and rates"},
      {check::kParamsSystem, group::kParameters, "system parameters (SYS_HITL)"},
      {check::kParamsCalibration, group::kParameters, "calibration IDs (CAL_*)"},
      {check::kParamsEkf2, group::kParameters, "EKF2 parameters"},
      {check::kParamsArming, group::kParameters, "arming relaxations"},
      {check::kParamsAllocation, group::kParameters, "control allocation (CA_*)"},
      {check::kEstimator, group::kEstimator, "EKF2 status and test ratios"},
      {check::kArming, group::kArming, "ready to arm"},
      {check::kVioOdometry, group::kVio, "ODOMETRY reaching the VIO port"},
      {check::kVioServer, group::kVio, "voxl-hitl-vio-server active"},
      {check::kVioPipe, group::kVio, "hitl_vio pipe"},
      {check::kVisionHub, group::kVio, "voxl-vision-hub en_hitl"},
      {check::kSession, group::kSimulator, "simulator session"},
      {check::kPaused, group::kSimulator, "not paused"},
      {check::kRealTime, group::kSimulator, "real-time factor"},
      {check::kLateTicks, group::kSimulator, "late ticks"},
      {check::kLoopLatency, group::kSimulator, "loop latency at the board"},
      {check::kPx4Build, group::kPx4, "PX4 SITL build (--px4 DIR)"},
      {check::kPx4Instance, group::kPx4, "PX4 instance and its ports"},
      {check::kPx4Connected, group::kPx4, "PX4 connected to the session"},
      {check::kPx4Params, group::kPx4, "PX4's parameters as hitl set them"},
  };
  return checks;
}

const CheckInfo& check_info(const std::string& id) {
  for (const auto& c : doctor_checks())
    if (id == c.id) return c;
  throw std::logic_error("hitl doctor: no check '" + id + "'");  // a programming error, never input
}

CheckResult make_result(const char* id, Verdict verdict, std::string saw, std::string fix) {
  CheckResult r;
  r.check = id;
  r.group = check_info(id).group;
  r.result = verdict;
  r.saw = std::move(saw);
  if (verdict == Verdict::Warn || verdict == Verdict::Fail) r.fix = std::move(fix);
  return r;
}

}  // namespace hitl::doctor
