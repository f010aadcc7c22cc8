// libFuzzer target for what hitl report reads from a recording's STATUSTEXT to shade the fault
// windows (engine/report/fault_windows.h): "t=20.000 s fault imu-vibration:8,90 started (5 s)". A
// text parses only with a finite time within bounds and a label without spaces; the windows built
// from the texts (each line one event) end no earlier than nothing and name their fault; the named
// arguments never fail. The same lines as the simulator's statement of its IMU's noise
// (engine/telemetry/imu_noise_statement.h, which the report's Allan plot marks): a parsed one has
// figures in [0, 1e6] and a profile name of at most 64 of [a-z0-9.-_], and says itself again.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/report/fault_windows.h"
#include "engine/telemetry/imu_noise_statement.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  std::vector<hitl::report::LogEvent> events;
  std::size_t at = 0;
  while (at <= text.size() && events.size() < 64) {
    auto end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::string line(text.substr(at, end - at));
    if (const auto c = hitl::report::parse_fault_change(line)) {
      FUZZ_CHECK(std::isfinite(c->t_s) && c->t_s >= 0 && c->t_s <= hitl::report::kMaxFaultTime_s);
      FUZZ_CHECK(!c->label.empty() && c->label.find(' ') == std::string::npos);
      FUZZ_CHECK(!c->duration_s || (c->started && std::isfinite(*c->duration_s) && *c->duration_s >= 0));
      (void)hitl::report::named_fault_args(c->label);
    }
    if (const auto f = hitl::telemetry::parse_imu_noise_statement(line)) {
      for (const double v : {f->gyro_noise_density, f->gyro_bias_instability, f->accel_noise_density, f->accel_bias_instability})
        FUZZ_CHECK(std::isfinite(v) && v >= 0 && v <= 1e6);
      FUZZ_CHECK(f->profile.size() <= 64);
      FUZZ_CHECK(hitl::telemetry::parse_imu_noise_statement(hitl::telemetry::imu_noise_statement(*f)).has_value());
    }
    events.push_back({static_cast<double>(events.size()), hitl::Severity::Info, "simulator", line});
    at = end + 1;
  }
  for (const bool simulated : {true, false})
    for (const auto& w : hitl::report::fault_windows(events, simulated)) {
      FUZZ_CHECK(!w.name.empty() && std::isfinite(w.start_s));
      FUZZ_CHECK(!w.end_s || std::isfinite(*w.end_s));
    }
  return 0;
}
