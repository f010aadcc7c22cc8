// The doctor's board sensor check (engine/doctor/sensor_checks) on fixed inputs: dsp_hitl's counters
// increasing at the spec's rates, or stalled, not running, missing or garbled.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "base/contract/dsp_hitl_status.h"
#include "engine/doctor/sensor_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

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

}  // namespace
}  // namespace hitl::doctor
