// hitl target's fault injection (emulator/faults.h): names, and the calibration check the
// wrong-cal-acc0-id fault trips (PX4 refuses to arm with a CAL_*_ID that names no present sensor).
#include <gtest/gtest.h>

#include "base/contract/device_ids.h"
#include "emulator/faults.h"
#include "emulator/flight_adapter.h"
#include "emulator/param_store.h"
#include "engine/vehicle/params_file.h"

namespace hitl::target {
namespace {

TEST(BoardFaults, NamesRoundTripAndBadNamesAreRefusedWithTheList) {
  ASSERT_EQ(fault_names().size(), 7u);
  for (const auto& name : fault_names()) {
    auto f = parse_fault(name);
    ASSERT_TRUE(f) << name;
    EXPECT_EQ(to_string(*f), name);
  }
  auto bad = parse_fault("no-gps");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("'no-gps'"), std::string::npos);
  EXPECT_NE(bad.error().message.find("dsp-hitl-stalled"), std::string::npos);
  BoardFaults faults;
  EXPECT_FALSE(faults.any());
  faults.set(Fault::SysHitl0);
  faults.set(Fault::WrongFlags);
  EXPECT_TRUE(faults.sys_hitl_0);
  EXPECT_EQ(faults.names(), "wrong-flags, sys-hitl-0");
}

TEST(BoardFaults, WrongAccelIdMakesTheAccelerometerUncalibratedAndArmingIsRefused) {
  ParamStore params;
  FlightAdapter flight(params);
  for (const auto& p : vehicle::hitl_default_params())
    if (params.get(p.name) == nullptr) params.add(p.name, p.value);
  EXPECT_EQ(flight.commander_check().find("uncalibrated"), std::string::npos);
  ASSERT_TRUE(params.set("CAL_ACC0_ID", vehicle::ParamValue::int32(kWrongAccelDeviceId)));
  const auto s = flight.state();
  EXPECT_FALSE(s.ready_to_arm);
  EXPECT_EQ(s.not_ready_reason, "Preflight Fail: Accel 0 uncalibrated");
  const auto r = flight.arm(false, 0);
  EXPECT_EQ(r.result, mavlink::MavResult::Denied);
  EXPECT_EQ(r.text, "Preflight Fail: Accel 0 uncalibrated");
  EXPECT_NE(flight.commander_check().find("Preflight check: FAILED"), std::string::npos);
  ASSERT_TRUE(params.set("CAL_ACC0_ID", vehicle::ParamValue::int32(static_cast<int32_t>(kDeviceIdImu))));
  ASSERT_TRUE(params.set("CAL_MAG0_ID", vehicle::ParamValue::int32(0)));
  EXPECT_EQ(flight.state().not_ready_reason, "Preflight Fail: Compass 0 uncalibrated");
}

}  // namespace
}  // namespace hitl::target
