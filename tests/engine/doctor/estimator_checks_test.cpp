// The doctor's estimator and arming checks (engine/doctor/estimator_checks) on fixed inputs: converged
// or not by the flags and ratios, ready to arm or the board's reasons in words.
#include <gtest/gtest.h>

#include <cmath>

#include "base/mavlink/enums.h"
#include "engine/doctor/estimator_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

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

// What PX4 v1.16 SITL sends at rest on the ground, fusing GNSS: flags 0x03BF (CONST_POS_MODE with
// the vehicle at rest, ekf_helper.cpp) and NaN for the range finder and airspeed it does not have.
TEST(DoctorEstimator, Px4AtRestWithGnssIsConverged) {
  EstimatorStatusSeen s = converged();
  s.flags = 0x03BF;
  s.hagl_ratio = std::nan("");
  s.tas_ratio = std::nan("");
  const auto r = estimator_check(s);
  EXPECT_EQ(r.result, Verdict::Pass) << r.saw;
  s.flags &= static_cast<uint16_t>(~mavlink::estimator_status::kPosHorizAbs);  // no GNSS: constant position is a fault
  const auto lost = estimator_check(s);
  EXPECT_EQ(lost.result, Verdict::Fail);
  EXPECT_TRUE(has(lost.saw, "const pos mode")) << lost.saw;
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

}  // namespace
}  // namespace hitl::doctor
