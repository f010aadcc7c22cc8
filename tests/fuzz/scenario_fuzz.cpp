// libFuzzer target for `hitl sim --scenario FILE` (issue 34: an event nested 70,000 arrays deep
// crashed building its error text; 1e400 aborted): the scenario parser, then a scenario that
// parses run through the fault schedule over simulated time with changing observations. What the
// faults fold into stays finite and within one fault's range, never more than kMaxActiveFaults
// active. The input is the whole file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/faults/fault_schedule.h"
#include "engine/faults/scenario.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  using namespace hitl::faults;
  const std::string text(reinterpret_cast<const char*>(bytes), size);
  auto specs = parse_scenario(text, "scenario 'fuzz.json'");
  if (!specs) {
    FUZZ_CHECK(!specs.error().message.empty() && specs.error().message.size() < 4096);
    FUZZ_CHECK(specs.error().kind == hitl::ErrorKind::Input);
    return 0;
  }
  FUZZ_CHECK(specs->size() <= kMaxScenarioEvents);
  FaultSchedule schedule(*specs);
  const char* modes[] = {"", "Position", "Land", "Hold"};
  for (int step = 0; step < 40; ++step) {
    const double t_s = step * 2.5;
    schedule.update(t_s, {static_cast<double>(step % 7) - 1.0, step > 3, modes[step % 4]});
    FUZZ_CHECK(schedule.active_count() <= kMaxActiveFaults);
    const ActiveFaults& a = schedule.active();
    for (double k : a.motor_effectiveness) FUZZ_CHECK(std::isfinite(k) && k >= 0 && k <= 2);
    FUZZ_CHECK(a.imu_noise_scale >= 0 && a.imu_noise_scale <= 100);
    FUZZ_CHECK(a.gps_noise_scale >= 0 && a.gps_noise_scale <= 100);
    FUZZ_CHECK(a.mag_scale >= 0 && a.mag_scale <= 10);
    FUZZ_CHECK(a.accel_bias_FRD_m_s2.allFinite() && a.gyro_bias_FRD_rad_s.allFinite() && a.wind_NED_m_s.allFinite());
    FUZZ_CHECK(std::isfinite(a.gps_north_m) && std::isfinite(a.baro_offset_Pa) && std::isfinite(a.payload_kg));
    for (const auto* link : {&a.hil_link, &a.vio_link}) {
      FUZZ_CHECK(link->drop_p >= 0 && link->drop_p <= 1 && link->reorder_p >= 0 && link->reorder_p <= 1);
      FUZZ_CHECK(std::isfinite(link->delay_s) && link->delay_s >= 0);
    }
  }
  return 0;
}
