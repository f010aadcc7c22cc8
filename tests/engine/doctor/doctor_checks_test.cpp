// Each doctor check's decision on fixed inputs: every verdict it can give, and that it names what
// it saw and the fix. No network, no processes.
#include <gtest/gtest.h>

#include "base/contract/session_status.h"
#include "base/mavlink/messages.h"
#include "engine/doctor/check_catalog.h"
#include "engine/doctor/estimator_checks.h"
#include "engine/doctor/host_checks.h"
#include "engine/doctor/host_probe.h"
#include "engine/doctor/link_checks.h"
#include "engine/doctor/observations.h"
#include "engine/doctor/param_checks.h"
#include "engine/doctor/sensor_checks.h"
#include "engine/doctor/simulator_checks.h"
#include "engine/doctor/vio_checks.h"

#include <cmath>
#include <limits>
#include "base/contract/dsp_hitl_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "engine/vehicle/params_check.h"

namespace hitl::doctor {
namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// --- catalogue and summary ------------------------------------------------------------------------
TEST(DoctorCatalog, ChecksAreUniqueGroupedAndInTheIssuesOrder) {
  const auto& checks = doctor_checks();
  ASSERT_EQ(checks.size(), 25u);
  std::set<std::string> ids;
  for (const auto& c : checks) EXPECT_TRUE(ids.insert(c.id).second) << c.id;
  const std::vector<std::string> groups = {group::kHost,     group::kLink,    group::kSensors, group::kParameters,
                                           group::kEstimator, group::kArming, group::kVio,     group::kSimulator};
  std::size_t g = 0;
  for (const auto& c : checks) {
    while (g < groups.size() && groups[g] != c.group) ++g;
    ASSERT_LT(g, groups.size()) << c.id << " is out of group order";
  }
  EXPECT_THROW(check_info("no-such-check"), std::logic_error);
}

TEST(DoctorCatalog, FixOnlyForWarningsAndFailuresAndTheWorstDecides) {
  EXPECT_TRUE(make_result(check::kRoute, Verdict::Pass, "x", "do y").fix.empty());
  EXPECT_TRUE(make_result(check::kRoute, Verdict::Skip, "x", "do y").fix.empty());
  EXPECT_EQ(make_result(check::kRoute, Verdict::Fail, "x", "do y").fix, "do y");
  EXPECT_EQ(make_result(check::kRoute, Verdict::Fail, "x").group, "host");
  const auto s = summarize({make_result(check::kRoute, Verdict::Pass, ""), make_result(check::kAdb, Verdict::Skip, ""),
                            make_result(check::kPorts, Verdict::Warn, "")});
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.worst, Verdict::Warn);
  const auto f = summarize({make_result(check::kRoute, Verdict::Fail, ""), make_result(check::kAdb, Verdict::Pass, "")});
  EXPECT_FALSE(f.ok());
  EXPECT_EQ(f.failed, 1u);
  EXPECT_STREQ(to_string(Verdict::Fail), "fail");
}

// --- host -----------------------------------------------------------------------------------------
NetInterface iface(const char* name, const char* ip, int prefix, bool up, bool running = true) {
  NetInterface i;
  i.name = name;
  i.address = *parse_ipv4(ip);
  i.netmask = prefix == 0 ? 0 : 0xFFFFFFFFu << (32 - prefix);
  i.up = up;
  i.running = running;
  return i;
}

TEST(DoctorHost, RouteToTheBoard) {
  const auto lo = iface("lo", "127.0.0.1", 8, true);
  const auto eth = iface("eth0", "10.0.0.5", 24, true);
  EXPECT_EQ(route_check("127.0.0.1", {lo}).result, Verdict::Skip);
  auto ok = route_check("192.168.101.2", {lo, eth, iface("usb0", "192.168.101.100", 24, true)});
  EXPECT_EQ(ok.result, Verdict::Pass);
  EXPECT_TRUE(has(ok.saw, "usb0 192.168.101.100/24 up")) << ok.saw;
  auto down = route_check("192.168.101.2", {iface("usb0", "192.168.101.100", 24, false, false)});
  EXPECT_EQ(down.result, Verdict::Fail);
  EXPECT_TRUE(has(down.fix, "ip link set usb0 up")) << down.fix;
  auto none = route_check("192.168.101.2", {lo, eth});
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.saw, "192.168.101.0/24")) << none.saw;
  EXPECT_TRUE(has(none.saw, "eth0 10.0.0.5/24 up")) << none.saw;
  EXPECT_TRUE(has(none.fix, "sudo ip addr add 192.168.101.100/24")) << none.fix;
  EXPECT_EQ(route_check("board.local", {eth}).result, Verdict::Fail);
}

TEST(DoctorHost, AdbDevices) {
  EXPECT_EQ(adb_check(false, "", Error{"x"}).result, Verdict::Skip);
  auto missing = adb_check(true, "", Error{"adb not found on PATH: install the Debian package adb"});
  EXPECT_EQ(missing.result, Verdict::Fail);
  EXPECT_TRUE(has(missing.fix, "apt-get install adb"));
  net::AdbDevices none{"/usr/bin/adb", {}};
  EXPECT_EQ(adb_check(true, "", none).result, Verdict::Fail);
  net::AdbDevices one{"/usr/bin/adb", {{"a1b2", "device"}}};
  EXPECT_EQ(adb_check(true, "", one).result, Verdict::Pass);
  EXPECT_EQ(adb_check(true, "zzz", one).result, Verdict::Fail);
  net::AdbDevices locked{"/usr/bin/adb", {{"a1b2", "unauthorized"}}};
  auto u = adb_check(true, "", locked);
  EXPECT_EQ(u.result, Verdict::Fail);
  EXPECT_TRUE(has(u.saw, "unauthorized")) << u.saw;
  net::AdbDevices two{"/usr/bin/adb", {{"a", "device"}, {"b", "device"}}};
  EXPECT_EQ(adb_check(true, "", two).result, Verdict::Fail);
  EXPECT_EQ(adb_check(true, "b", two).result, Verdict::Pass);
}

PortProbe probe(uint16_t port, bool taken, std::vector<PortHolder> holders = {}) {
  PortProbe p;
  p.port = port;
  p.role = port == 14560 ? "HIL" : "VIO";
  p.taken = taken;
  p.holders = std::move(holders);
  return p;
}

TEST(DoctorHost, PortsFreeForARemoteBoardHeldByTheStandInForALocalOne) {
  const PortHolder hitl{4242, "hitl target --hil-port 14560", "hitl"};
  const PortHolder python{777, "python3 -c import socket ...", "python3"};
  EXPECT_EQ(ports_check({probe(14560, false), probe(14570, false)}, false).result, Verdict::Pass);
  auto listener = ports_check({probe(14560, false), probe(14570, true, {python})}, false);
  EXPECT_EQ(listener.result, Verdict::Fail);
  EXPECT_TRUE(has(listener.saw, "VIO UDP 14570 is taken by 'python3 -c import socket ...' (pid 777)")) << listener.saw;
  EXPECT_TRUE(has(listener.fix, "kill 777")) << listener.fix;
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, true, {hitl})}, true).result, Verdict::Pass);
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, true, {python})}, true).result, Verdict::Fail);
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, false)}, true).result, Verdict::Warn);
  EXPECT_EQ(ports_check({probe(14560, true)}, false).result, Verdict::Fail);  // someone this user cannot see
  EXPECT_EQ(ports_check({probe(14560, true)}, true).result, Verdict::Warn);
}

TEST(DoctorHost, ProcNetUdpInodes) {
  const std::string table =
      "  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode ref pointer drops\n"
      "  311: 0100007F:38E0 00000000:0000 07 00000000:00000000 00:00000000 00000000  1000        0 987654 2 0 0\n"
      "  312: 00000000:38EA 00000000:0000 07 00000000:00000000 00:00000000 00000000  1000        0 123 2 0 0\n"
      "garbage line\n";
  EXPECT_EQ(udp_inodes_for_port(table, 14560), std::vector<uint64_t>{987654});  // 0x38E0
  EXPECT_EQ(udp_inodes_for_port(table, 14570), std::vector<uint64_t>{123});     // 0x38EA
  EXPECT_TRUE(udp_inodes_for_port(table, 14558).empty());
  EXPECT_TRUE(udp_inodes_for_port("", 14560).empty());
  EXPECT_TRUE(is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(is_loopback_host("localhost"));
  EXPECT_FALSE(is_loopback_host("192.168.101.2"));
}

// --- link -----------------------------------------------------------------------------------------
HeartbeatSeen px4_heartbeat(uint8_t base_mode) {
  HeartbeatSeen h;
  h.sysid = 1;
  h.autopilot = 12;
  h.base_mode = base_mode;
  h.custom_mode = 3u << 16;
  h.count = 3;
  h.first_s = 10;
  h.last_s = 12;
  return h;
}

TEST(DoctorLink, HeartbeatAndHilMode) {
  auto none = heartbeat_check(Error{"no autopilot HEARTBEAT direct to 127.0.0.1:14558"}, std::nullopt);
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.fix, "hitl target"));
  const auto hil = px4_heartbeat(mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kHilEnabled);
  auto ok = heartbeat_check(std::string("through the session on 127.0.0.1:14600"), hil);
  EXPECT_EQ(ok.result, Verdict::Pass);
  EXPECT_TRUE(has(ok.saw, "PX4 system 1 through the session")) << ok.saw;
  EXPECT_TRUE(has(ok.saw, "1.0 Hz")) << ok.saw;
  EXPECT_EQ(hil_mode_check(hil).result, Verdict::Pass);
  auto no_hil = hil_mode_check(px4_heartbeat(mavlink::mode_flag::kCustomModeEnabled));
  EXPECT_EQ(no_hil.result, Verdict::Fail);
  EXPECT_TRUE(has(no_hil.fix, "SYS_HITL 1")) << no_hil.fix;
  EXPECT_EQ(hil_mode_check(std::nullopt).result, Verdict::Skip);
}

TEST(DoctorLink, MavlinkStatusOfPx4AndOfHitlTarget) {
  const std::string px4 =
      "\ninstance #0:\n\tGCS heartbeat valid\n\tmavlink chan: #0\n\ttype:\t\tGENERIC LINK OR RADIO\n"
      "\ttransport protocol: UDP (14560, remote port: 14561)\n\tBroadcast enabled: NO\n"
      "instance #1:\n\ttransport protocol: UDP (14556, remote port: 14557)\n"
      "instance #2:\n\ttransport protocol: UDP (14558, remote port: 14562)\n";
  const auto seen = parse_mavlink_status(px4);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].udp_port, 14560);
  EXPECT_EQ(seen[0].remote, "14561");
  EXPECT_EQ(seen[2].udp_port, 14558);
  EXPECT_EQ(mavlink_instances_check(px4, 14560).result, Verdict::Pass);
  auto missing = mavlink_instances_check(px4, 14999);
  EXPECT_EQ(missing.result, Verdict::Fail);
  EXPECT_TRUE(has(missing.saw, "no instance on the HIL port UDP 14999")) << missing.saw;
  const std::string emulator =
      "instance #0 (HIL instance (--hil-port)):\n\tUDP (40000, remote port: none)\n\tpartner: none yet\n";
  EXPECT_EQ(mavlink_instances_check(emulator, 40000).result, Verdict::Pass);
  EXPECT_EQ(mavlink_instances_check(std::string("nsh: mavlink: command not found\n"), 14560).result, Verdict::Warn);
  EXPECT_EQ(mavlink_instances_check(Error{"timeout"}, 14560).result, Verdict::Warn);
}

SessionStatus session(bool lockstep, double rtf, double act_hz, int32_t flags, int32_t armed) {
  SessionStatus s;
  s.sysid = 250;
  s.reports = 2;
  s.rtf = rtf;
  s.speed = rtf;
  s.paused = false;
  s.lockstep = lockstep;
  s.actuator_hz = act_hz;
  s.actuator_flags = flags;
  s.actuator_armed = armed;
  return s;
}

TEST(DoctorLink, ActuatorRateAgainstLockstepOrTheBoardsStream) {
  EXPECT_DOUBLE_EQ(*expected_actuator_rate_hz(session(true, 5, 0, -1, -1)), 1250.0);
  EXPECT_DOUBLE_EQ(*expected_actuator_rate_hz(session(false, 1, 0, -1, -1)), 200.0);
  EXPECT_EQ(actuators_check(session(true, 5, 1240, 15, 0)).result, Verdict::Pass);
  EXPECT_EQ(actuators_check(session(false, 1, 199, 15, 0)).result, Verdict::Pass);
  EXPECT_EQ(actuators_check(session(false, 1, 140, 15, 0)).result, Verdict::Warn);
  EXPECT_EQ(actuators_check(session(false, 1, 50, 15, 0)).result, Verdict::Fail);
  auto none = actuators_check(session(true, 5, 0, -1, -1));
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.saw, "none ever")) << none.saw;
  EXPECT_TRUE(has(none.fix, "HIL_ACTUATOR_CONTROLS -r 200")) << none.fix;
  EXPECT_EQ(actuators_check(SessionStatus{}).result, Verdict::Skip);
}

TEST(DoctorLink, FlagsAndArmedBit) {
  EXPECT_EQ(actuator_flags_check(session(true, 1, 250, 0x0F, 0)).result, Verdict::Pass);
  auto wrong = actuator_flags_check(session(true, 1, 250, 0x00, 0));
  EXPECT_EQ(wrong.result, Verdict::Fail);
  EXPECT_TRUE(has(wrong.saw, "flags 0x00")) << wrong.saw;
  EXPECT_EQ(actuator_flags_check(session(true, 1, 0, -1, -1)).result, Verdict::Skip);
  const auto disarmed = px4_heartbeat(mavlink::mode_flag::kHilEnabled);
  const auto armed = px4_heartbeat(mavlink::mode_flag::kHilEnabled | mavlink::mode_flag::kSafetyArmed);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 0), disarmed).result, Verdict::Pass);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 1), armed).result, Verdict::Pass);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 1), disarmed).result, Verdict::Fail);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, -1), disarmed).result, Verdict::Skip);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 0), std::nullopt).result, Verdict::Skip);
}

// --- board sensors ---------------------------------------------------------------------------------
std::string dsp_text(bool running, uint64_t imu, uint64_t mag_baro, uint64_t mag, uint64_t baro) {
  target::DspHitlCounters c;
  c.hil_imu_received = imu;
  c.imu_published = imu;
  c.hil_mag_baro_received = mag_baro;
  c.mag_published = mag;
  c.baro_published = baro;
  target::DspHitlCurrent cur;
  return target::dsp_hitl_status_text(running, c, cur);
}

TEST(DoctorSensors, CountersIncreasingAtTheSpecsRates) {
  const DspHitlRead a{dsp_text(true, 1000, 400, 200, 40), 10.0};
  const DspHitlRead b{dsp_text(true, 1500, 600, 300, 60), 12.0};  // 250, 100, 50, 10 Hz
  auto ok = dsp_hitl_check(a, b, 1.0, true);
  EXPECT_EQ(ok.result, Verdict::Pass) << ok.saw;
  EXPECT_TRUE(has(ok.saw, "HIL sensor_imu received 250/250 Hz")) << ok.saw;
  EXPECT_TRUE(dsp_hitl_counting(a, b));
  // The same counts at a pace of 5 (lockstep at --speed 5) are 5 times too slow.
  EXPECT_EQ(dsp_hitl_check(a, b, 5.0, true).result, Verdict::Fail);
  EXPECT_EQ(dsp_hitl_check(a, DspHitlRead{dsp_text(true, 1360, 545, 270, 54), 12.0}, 1.0, true).result, Verdict::Warn);
}

TEST(DoctorSensors, StalledNotRunningMissingOrGarbled) {
  const DspHitlRead a{dsp_text(true, 500, 200, 100, 20), 10.0};
  auto stalled = dsp_hitl_check(a, DspHitlRead{dsp_text(true, 500, 200, 100, 20), 11.5}, 1.0, true);
  EXPECT_EQ(stalled.result, Verdict::Fail);
  EXPECT_TRUE(has(stalled.saw, "counters stopped")) << stalled.saw;
  EXPECT_TRUE(has(stalled.fix, "MUORB")) << stalled.fix;
  EXPECT_TRUE(has(dsp_hitl_check(a, DspHitlRead{dsp_text(true, 500, 200, 100, 20), 11.5}, 1.0, std::nullopt).fix, "hitl sim"));
  EXPECT_FALSE(dsp_hitl_counting(a, DspHitlRead{dsp_text(true, 500, 200, 100, 20), 11.5}));
  EXPECT_EQ(dsp_hitl_check(a, DspHitlRead{dsp_text(true, 900, 200, 100, 20), 11.5}, 1.0, true).result, Verdict::Fail);
  auto stopped = dsp_hitl_check(a, DspHitlRead{dsp_text(false, 500, 200, 100, 20), 11.5}, 1.0, true);
  EXPECT_EQ(stopped.result, Verdict::Fail);
  EXPECT_TRUE(has(stopped.fix, "dsp_hitl start")) << stopped.fix;
  const DspHitlRead sitl{std::string("nsh: dsp_hitl: command not found\n"), 10.0};
  EXPECT_EQ(dsp_hitl_check(sitl, sitl, 1.0, true).result, Verdict::Skip);
  EXPECT_EQ(dsp_hitl_check(DspHitlRead{std::string("garbage"), 1}, a, 1.0, true).result, Verdict::Fail);
  EXPECT_EQ(dsp_hitl_check(DspHitlRead{Error{"the shell did not answer"}, 1}, a, 1.0, true).result, Verdict::Fail);
}

// --- parameters ------------------------------------------------------------------------------------
std::vector<vehicle::Param> defaults_with(const std::string& name, vehicle::ParamValue value) {
  auto p = vehicle::hitl_default_params();
  for (auto& x : p)
    if (x.name == name) x.value = value;
  return p;
}

std::vector<std::string> failing(const std::vector<CheckResult>& results) {
  std::vector<std::string> out;
  for (const auto& r : results)
    if (r.result == Verdict::Fail) out.push_back(r.check);
  return out;
}

TEST(DoctorParams, OneCheckPerCategoryFailsAlone) {
  const auto all = param_checks(vehicle::hitl_default_params());
  ASSERT_EQ(all.size(), 5u);
  EXPECT_TRUE(failing(all).empty());
  auto sys = param_checks(defaults_with("SYS_HITL", vehicle::ParamValue::int32(0)));
  EXPECT_EQ(failing(sys), std::vector<std::string>{check::kParamsSystem});
  EXPECT_TRUE(has(sys[0].saw, "SYS_HITL 0 (spec 1)")) << sys[0].saw;
  EXPECT_TRUE(has(sys[0].fix, "hitl params set SYS_HITL 1")) << sys[0].fix;
  auto cal = param_checks(defaults_with("CAL_ACC0_ID", vehicle::ParamValue::int32(1311244)));
  EXPECT_EQ(failing(cal), std::vector<std::string>{check::kParamsCalibration});
  EXPECT_TRUE(has(cal[1].saw, "dsp_hitl's IMU is 1310988")) << cal[1].saw;
  auto ekf = param_checks(defaults_with("EKF2_GPS_CTRL", vehicle::ParamValue::int32(1)));
  EXPECT_EQ(failing(ekf), std::vector<std::string>{check::kParamsEkf2});
  auto arm = param_checks(defaults_with("CBRK_SUPPLY_CHK", vehicle::ParamValue::int32(0)));
  EXPECT_EQ(failing(arm), std::vector<std::string>{check::kParamsArming});
  auto ca = param_checks(defaults_with("CA_ROTOR0_KM", vehicle::ParamValue::real32(-0.05f)));
  EXPECT_EQ(failing(ca), std::vector<std::string>{check::kParamsAllocation});
  auto gone = param_checks(Error{"no PARAM_VALUE in answer to PARAM_REQUEST_LIST"});
  EXPECT_EQ(failing(gone), std::vector<std::string>{check::kParamsSystem});
  EXPECT_EQ(gone[4].result, Verdict::Skip);
}

TEST(DoctorParams, TheSharedCheckOfHitlParamsCheck) {
  auto board = vehicle::hitl_default_params();
  board.erase(board.begin());  // SYS_AUTOSTART missing
  const auto rows = vehicle::check_params(board, vehicle::hitl_default_params());
  ASSERT_EQ(rows.size(), vehicle::hitl_default_params().size());
  EXPECT_FALSE(rows[0].ok);
  EXPECT_FALSE(rows[0].board.has_value());
  EXPECT_TRUE(has(rows[0].fix, "lacks SYS_AUTOSTART"));
  EXPECT_TRUE(rows[1].ok);
  EXPECT_EQ(vehicle::param_group("CAL_MAG0_ID"), vehicle::ParamGroup::Calibration);
  EXPECT_EQ(vehicle::param_group("COM_ARM_EKF_POS"), vehicle::ParamGroup::Arming);
  EXPECT_EQ(vehicle::param_group("CA_ROTOR_COUNT"), vehicle::ParamGroup::ControlAllocation);
  EXPECT_EQ(vehicle::param_group("IMU_GYRO_RATEMAX"), vehicle::ParamGroup::System);
}

// --- estimator, arming -----------------------------------------------------------------------------
EstimatorStatusSeen converged() {
  namespace e = mavlink::estimator_status;
  EstimatorStatusSeen s;
  s.flags = e::kAttitude | e::kVelocityHoriz | e::kVelocityVert | e::kPosHorizRel | e::kPosHorizAbs | e::kPosVertAbs |
            e::kPredPosHorizRel | e::kPredPosHorizAbs;
  s.vel_ratio = 0.1;
  s.pos_horiz_ratio = 0.05;
  s.pos_vert_ratio = 0.2;
  return s;
}

TEST(DoctorEstimator, ConvergedNotConvergedRatios) {
  EXPECT_EQ(estimator_check(std::nullopt).result, Verdict::Skip);
  EXPECT_EQ(estimator_check(converged()).result, Verdict::Pass);
  auto s = converged();
  s.flags &= static_cast<uint16_t>(~mavlink::estimator_status::kPosHorizAbs);
  auto pending = estimator_check(s);
  EXPECT_EQ(pending.result, Verdict::Fail);
  EXPECT_TRUE(has(pending.saw, "not converged (no pos horiz abs)")) << pending.saw;
  s = converged();
  s.vel_ratio = 12.5;
  auto high = estimator_check(s);
  EXPECT_EQ(high.result, Verdict::Fail);
  EXPECT_TRUE(has(high.saw, "velocity 12.50")) << high.saw;
  s = converged();
  s.pos_vert_ratio = 0.7;
  EXPECT_EQ(estimator_check(s).result, Verdict::Warn);
  s = converged();
  s.flags |= mavlink::estimator_status::kGpsGlitch;
  EXPECT_TRUE(has(estimator_check(s).saw, "GPS glitch"));
  s = converged();
  s.mag_ratio = std::nan("");
  EXPECT_EQ(estimator_check(s).result, Verdict::Fail);
}

SysStatusSeen sys_status(bool ready) {
  namespace b = mavlink::sys_status;
  SysStatusSeen s;
  s.present = s.enabled = b::kGyro | b::kAccel | b::kPrearmCheck;
  s.health = b::kGyro | (ready ? b::kAccel | b::kPrearmCheck : 0);
  return s;
}

TEST(DoctorArming, ReadyOrTheBoardsReasonsInWords) {
  const auto hb = px4_heartbeat(mavlink::mode_flag::kHilEnabled);
  EXPECT_EQ(arming_check(hb, sys_status(true), {}, Error{"not needed"}).result, Verdict::Pass);
  auto cal = arming_check(hb, sys_status(false), {"hitl target: an emulated VOXL2 board, not PX4"},
                          std::string("Preflight Fail: Accel 0 uncalibrated\nPreflight check: FAILED\n"));
  EXPECT_EQ(cal.result, Verdict::Fail);
  EXPECT_TRUE(has(cal.saw, "Preflight Fail: Accel 0 uncalibrated")) << cal.saw;
  EXPECT_TRUE(has(cal.saw, "SYS_STATUS unhealthy: accelerometer")) << cal.saw;
  EXPECT_TRUE(has(cal.fix, "hitl params reset")) << cal.fix;
  auto ekf = arming_check(hb, sys_status(false), {"Preflight Fail: Velocity estimate error"}, Error{"timeout"});
  EXPECT_TRUE(has(ekf.fix, "estimator")) << ekf.fix;
  EXPECT_EQ(arming_check(hb, std::nullopt, {}, std::string("Preflight check: OK\n")).result, Verdict::Pass);
  EXPECT_EQ(arming_check(hb, std::nullopt, {}, Error{"no shell"}).result, Verdict::Skip);
  EXPECT_EQ(arming_check(px4_heartbeat(mavlink::mode_flag::kSafetyArmed), sys_status(false), {}, Error{""}).result, Verdict::Pass);
  EXPECT_EQ(preflight_failures({"Preflight Fail: a", "x", "[cmd] Preflight Fail: a"}, "Preflight Fail: b\r\n"),
            (std::vector<std::string>{"Preflight Fail: a", "Preflight Fail: b"}));
}

// --- VIO --------------------------------------------------------------------------------------------
TEST(DoctorVio, ServerReportPipeAndVisionHub) {
  const std::string report = R"({"running":true,"listen":"0.0.0.0:14570","odometry_rate_hz":249.6,"odometry":12000})";
  EXPECT_EQ(vio_odometry_check(report, 250).result, Verdict::Pass);
  EXPECT_EQ(vio_odometry_check("voxl-hitl-vio-server --status --json\n" + report + "\n", 250).result, Verdict::Pass);
  EXPECT_EQ(vio_odometry_check(report, 1250).result, Verdict::Fail);
  EXPECT_EQ(vio_odometry_check(std::string(R"({"running":true,"listen":"0.0.0.0:14570","odometry_rate_hz":0})"), 250).result, Verdict::Fail);
  auto down = vio_odometry_check(std::string(R"({"running":false,"error":"voxl-hitl-vio-server is not running"})"), 250);
  EXPECT_EQ(down.result, Verdict::Fail);
  EXPECT_TRUE(has(down.fix, "systemctl enable --now voxl-hitl-vio-server")) << down.fix;
  EXPECT_EQ(vio_odometry_check(std::string("sh: voxl-hitl-vio-server: not found"), 250).result, Verdict::Fail);
  EXPECT_EQ(vio_odometry_check(Error{"needs adb"}, 250).result, Verdict::Skip);
  EXPECT_EQ(vio_server_check(std::string("active\n")).result, Verdict::Pass);
  EXPECT_EQ(vio_server_check(std::string("inactive\n")).result, Verdict::Fail);
  EXPECT_EQ(vio_server_check(Error{"needs adb"}).result, Verdict::Skip);
  EXPECT_EQ(vio_pipe_check(std::string("hitl_vio/\nhitl_vio_extended/\nimu_apps/\n")).result, Verdict::Pass);
  EXPECT_EQ(vio_pipe_check(std::string("hitl_vio_extended\nqvio\n")).result, Verdict::Fail);
  const std::string hub = "{\n  // the spec's settings\n  \"en_vio\": false, \"vio_pipe\": \"qvio\", \"en_hitl\": true, \"offboard_mode\": \"vfc\"\n}";
  auto ok = vision_hub_check(hub);
  EXPECT_EQ(ok.result, Verdict::Pass) << ok.saw;
  EXPECT_TRUE(has(ok.saw, "offboard_mode vfc"));
  EXPECT_EQ(vision_hub_check(std::string(R"({"en_hitl": false})")).result, Verdict::Fail);
  EXPECT_EQ(vision_hub_check(std::string(R"({"en_vio": true})")).result, Verdict::Fail);
  EXPECT_EQ(vision_hub_check(std::string("cat: /etc/modalai/voxl-vision-hub.conf: No such file")).result, Verdict::Fail);
}

// --- simulator ---------------------------------------------------------------------------------------
TEST(DoctorSimulator, SessionPausedPaceLateTicks) {
  SessionStatus none;
  EXPECT_EQ(session_check(none, 14600, false).result, Verdict::Fail);
  EXPECT_EQ(session_check(none, 14600, true).result, Verdict::Warn);
  EXPECT_EQ(session_check(none, 14600, std::nullopt).result, Verdict::Fail);
  EXPECT_EQ(paused_check(none).result, Verdict::Skip);
  auto s = session(true, 5, 1250, 15, 0);
  EXPECT_EQ(session_check(s, 14600, true).result, Verdict::Pass);
  EXPECT_EQ(paused_check(s).result, Verdict::Pass);
  s.paused = true;
  EXPECT_EQ(paused_check(s).result, Verdict::Fail);
  s = session(false, 0.6, 200, 15, 0);
  s.speed = 1.0;
  EXPECT_EQ(real_time_check(s).result, Verdict::Fail);
  s.lockstep = true;
  EXPECT_EQ(real_time_check(s).result, Verdict::Warn);
  s.speed = 0.0;
  EXPECT_EQ(real_time_check(s).result, Verdict::Pass);
  s = session(false, 1.0, 200, 15, 0);
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Skip);
  s.first_late = SessionStatus::LateSample{10.0, 3};
  s.last_late = SessionStatus::LateSample{12.0, 3};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Pass);
  s.last_late = SessionStatus::LateSample{12.0, 10};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Warn);  // 7 of 500
  s.last_late = SessionStatus::LateSample{12.0, 100};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Fail);  // 97 of 500
  s.lockstep = true;
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Warn);
}

// --- what the link carries ----------------------------------------------------------------------------
TEST(DoctorObservations, AutopilotAndSessionStatusFromFrames) {
  static const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  ObservationTracker tracker;
  auto feed = [&](auto message, uint8_t sysid, bool autopilot, double t_s) {
    mavlink::FrameEncoder enc(sysid, 1);
    mavlink::FrameBuffer buf;
    const auto n = enc.encode(message, buf);
    parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) {
      if (autopilot) tracker.on_autopilot_frame(f, t_s);
      else tracker.on_other_frame(f, t_s);
    });
  };
  mavlink::msg::Heartbeat hb;
  hb.autopilot = 12;
  hb.base_mode = mavlink::mode_flag::kHilEnabled | mavlink::mode_flag::kSafetyArmed;
  feed(hb, 1, true, 1.0);
  feed(hb, 1, true, 2.0);
  auto named_float = [](std::string_view name, float v) {
    mavlink::msg::NamedValueFloat m;
    std::copy(name.begin(), name.end(), m.name.begin());
    m.value = v;
    return m;
  };
  auto named_int = [](std::string_view name, int32_t v) {
    mavlink::msg::NamedValueInt m;
    std::copy(name.begin(), name.end(), m.name.begin());
    m.value = v;
    return m;
  };
  feed(named_int(hitl::kStatusLateName, 4), 250, false, 1.0);  // before sim_rtf: not yet known as the session
  feed(named_float(hitl::kStatusRtfName, 4.9f), 250, false, 1.0);
  feed(named_int(hitl::kStatusLateName, 5), 250, false, 1.0);
  feed(named_float(hitl::kStatusSpeedName, 5.0f), 250, false, 1.0);
  feed(named_int(hitl::kStatusLockstepName, 1), 250, false, 1.0);
  feed(named_float(hitl::kStatusActuatorRateName, 1230.0f), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorFlagsName, 15), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorArmedName, 1), 250, false, 1.0);
  feed(named_int(hitl::kStatusPauseName, 0), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorFlagsName, 0), 77, false, 1.5);  // another system: ignored
  feed(named_float(hitl::kStatusRtfName, 5.0f), 250, false, 2.0);
  feed(named_int(hitl::kStatusLateName, 9), 250, false, 2.0);
  mavlink::msg::Statustext st;
  const std::string text = "Preflight Fail: ekf2 not aligned";
  std::copy(text.begin(), text.end(), st.text.begin());
  feed(st, 1, true, 2.0);
  const auto& seen = tracker.observations();
  ASSERT_TRUE(seen.heartbeat);
  EXPECT_EQ(seen.heartbeat->count, 2u);
  EXPECT_TRUE(seen.heartbeat->armed());
  const auto& s = seen.session;
  EXPECT_TRUE(s.heard());
  EXPECT_EQ(s.reports, 2u);
  EXPECT_EQ(*s.sysid, 250);
  EXPECT_FLOAT_EQ(static_cast<float>(*s.rtf), 5.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(*s.speed), 5.0f);
  EXPECT_TRUE(*s.lockstep);
  EXPECT_FALSE(*s.paused);
  EXPECT_EQ(*s.actuator_flags, 15);
  EXPECT_EQ(*s.actuator_armed, 1);
  EXPECT_EQ(s.first_late->late, 5);
  EXPECT_EQ(s.last_late->late, 9);
  EXPECT_EQ(seen.statustext, std::vector<std::string>{text});
}

}  // namespace
}  // namespace hitl::doctor
