// The doctor's PX4 SITL checks (engine/doctor/px4_checks) on fixed inputs: the build found or what
// is missing, the instance held or the one hitl sim --px4 would take, PX4 connected through the
// session, and its parameters against those hitl gave it.
#include <gtest/gtest.h>

#include "engine/doctor/px4_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

px4::Px4Build a_build(const std::string& version = "v1.16.0", bool lockstep = true) {
  px4::Px4Build b;
  b.build_dir = "/px4/build/px4_sitl_default";
  b.version = version;
  b.lockstep = lockstep;
  return b;
}

SessionStatus px4_session(int instance) {
  SessionStatus s = session(true, 1.0, 250, 1, 0);
  s.px4_instance = instance;
  return s;
}

TEST(DoctorPx4, BuildFoundWithItsVersionOrWhatIsMissing) {
  Px4Findings f;
  EXPECT_EQ(px4_build_check(f).result, Verdict::Skip);
  f.build = Expected<px4::Px4Build>(Error::input("'/tmp' is not a PX4 SITL build: no bin/px4"));
  auto missing = px4_build_check(f);
  EXPECT_EQ(missing.result, Verdict::Fail);
  EXPECT_TRUE(has(missing.saw, "no bin/px4")) << missing.saw;
  EXPECT_TRUE(has(missing.fix, "scripts/px4-sitl.sh")) << missing.fix;
  f.build = Expected<px4::Px4Build>(a_build());
  auto found = px4_build_check(f);
  EXPECT_EQ(found.result, Verdict::Pass);
  EXPECT_TRUE(has(found.saw, "PX4 v1.16.0 SITL at /px4/build/px4_sitl_default (lockstep)")) << found.saw;
  f.build = Expected<px4::Px4Build>(a_build("v1.16.0", false));
  EXPECT_EQ(px4_build_check(f).result, Verdict::Fail);
  f.build = Expected<px4::Px4Build>(a_build(""));
  EXPECT_EQ(px4_build_check(f).result, Verdict::Warn);
}

TEST(DoctorPx4, InstanceHeldByTheSessionOrTheOneHitlWouldTake) {
  Px4Findings f;
  const SessionStatus none;
  EXPECT_EQ(px4_instance_check(f, none).result, Verdict::Skip);
  auto held = px4_instance_check(f, px4_session(2));
  EXPECT_EQ(held.result, Verdict::Pass);
  EXPECT_TRUE(has(held.saw, "instance 2 (TCP 4562, GCS UDP 18572, system id 3)")) << held.saw;
  EXPECT_EQ(px4_instance_check(f, px4_session(-1)).result, Verdict::Warn);
  f.build = Expected<px4::Px4Build>(a_build());
  f.first_free = 0;
  auto free0 = px4_instance_check(f, none);
  EXPECT_EQ(free0.result, Verdict::Pass);
  EXPECT_TRUE(has(free0.saw, "takes instance 0 (TCP 4560")) << free0.saw;
  f.busy = {{0, "a PX4 runs as instance 0 (/tmp/px4_lock-0 is locked)"}};
  f.first_free = 1;
  auto busy = px4_instance_check(f, none);
  EXPECT_EQ(busy.result, Verdict::Warn);
  EXPECT_TRUE(has(busy.saw, "instance 0: a PX4 runs as instance 0")) << busy.saw;
  EXPECT_TRUE(has(busy.saw, "takes instance 1")) << busy.saw;
  f.first_free.reset();
  EXPECT_EQ(px4_instance_check(f, none).result, Verdict::Fail);
}

TEST(DoctorPx4, ConnectedThroughTheSessionWithItsVersion) {
  Px4Findings f;
  const SessionStatus none;
  EXPECT_EQ(px4_connected_check(f, none, std::nullopt).result, Verdict::Skip);
  EXPECT_EQ(px4_connected_check(f, session(true, 1, 250, 1, 0), px4_heartbeat(0)).result, Verdict::Skip);  // a board
  EXPECT_EQ(px4_connected_check(f, px4_session(-1), std::nullopt).result, Verdict::Fail);
  f.running_version = "v1.16.0";
  auto up = px4_connected_check(f, px4_session(0), px4_heartbeat(0));
  EXPECT_EQ(up.result, Verdict::Pass) << up.saw;
  EXPECT_TRUE(has(up.saw, "PX4 v1.16.0, instance 0")) << up.saw;
  auto other = px4_heartbeat(0);
  other.sysid = 7;
  auto wrong = px4_connected_check(f, px4_session(0), other);
  EXPECT_EQ(wrong.result, Verdict::Fail);
  EXPECT_TRUE(has(wrong.saw, "heard system 7")) << wrong.saw;
  f.build = Expected<px4::Px4Build>(a_build("v1.15.4"));
  EXPECT_EQ(px4_connected_check(f, px4_session(0), px4_heartbeat(0)).result, Verdict::Warn);
}

TEST(DoctorPx4, ParametersAgainstThoseHitlGave) {
  Px4Findings f;
  f.expected = {{"CA_ROTOR_COUNT", "4"}, {"MPC_THR_HOVER", "0.5903"}, {"SYS_FAILURE_EN", "1"}};
  std::vector<vehicle::Param> have = {{"CA_ROTOR_COUNT", vehicle::ParamValue::int32(4)},
                                      {"MPC_THR_HOVER", vehicle::ParamValue::real32(0.5903f)},
                                      {"SYS_FAILURE_EN", vehicle::ParamValue::int32(1)}};
  EXPECT_EQ(px4_params_check(f, SessionStatus{}, have).result, Verdict::Skip);
  auto as_set = px4_params_check(f, px4_session(0), have);
  EXPECT_EQ(as_set.result, Verdict::Pass) << as_set.saw;
  EXPECT_TRUE(has(as_set.saw, "the 3 parameters hitl gave PX4 are as set")) << as_set.saw;
  have[1].value = vehicle::ParamValue::real32(0.5f);
  auto changed = px4_params_check(f, px4_session(0), have);
  EXPECT_EQ(changed.result, Verdict::Warn);
  EXPECT_TRUE(has(changed.saw, "MPC_THR_HOVER 0.5 (hitl set 0.5903)")) << changed.saw;
  have.pop_back();
  auto absent = px4_params_check(f, px4_session(0), have);
  EXPECT_EQ(absent.result, Verdict::Fail);
  EXPECT_TRUE(has(absent.saw, "PX4 has no SYS_FAILURE_EN")) << absent.saw;
  EXPECT_EQ(px4_params_check(f, px4_session(0), Error::failed("timed out")).result, Verdict::Fail);
}

}  // namespace
}  // namespace hitl::doctor
