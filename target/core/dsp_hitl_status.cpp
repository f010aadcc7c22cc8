#include "target/core/dsp_hitl_status.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "target/core/dsp_hitl.h"

namespace hitl::target {

namespace {

#if defined(__GNUC__)
#define HITL_PRINTF_FORMAT(fmt, first) __attribute__((format(printf, fmt, first)))
#else
#define HITL_PRINTF_FORMAT(fmt, first)
#endif

/// Appends printf output at `*used`, keeping track of the full length even past `size`.
void append(char* buffer, std::size_t size, std::size_t* used, const char* format, ...) HITL_PRINTF_FORMAT(4, 5);

void append(char* buffer, std::size_t size, std::size_t* used, const char* format, ...) {
  char* at = (buffer != nullptr && *used < size) ? buffer + *used : nullptr;
  const std::size_t room = (at != nullptr) ? size - *used : 0;
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(at, room, format, args);
  va_end(args);
  if (n > 0) *used += static_cast<std::size_t>(n);
}

/// "%.3f" without a negative zero: values that round to 0.000 print as "0.000".
double shown(float value) {
  const double v = static_cast<double>(value);
  return (std::isfinite(v) && std::fabs(v) < 0.0005) ? 0.0 : v;
}

void append_vector(char* buffer, std::size_t size, std::size_t* used, const char* label, bool received,
                   const float (&v)[3]) {
  if (!received) {
    append(buffer, size, used, "  Current %s (x,y,z): no data\n", label);
  } else {
    append(buffer, size, used, "  Current %s (x,y,z): %.3f, %.3f, %.3f\n", label, shown(v[0]), shown(v[1]),
           shown(v[2]));
  }
}

unsigned long long u(uint64_t n) { return static_cast<unsigned long long>(n); }

}  // namespace

std::size_t format_dsp_hitl_status(char* buffer, std::size_t size, bool running, const DspHitlCounters& counters,
                                   const DspHitlCurrent& current) {
  if (buffer != nullptr && size > 0) buffer[0] = '\0';
  std::size_t used = 0;
  append(buffer, size, &used, "Running: %s\n", running ? "yes" : "no");
  append(buffer, size, &used, "%s", "=== IMU Section ===\n");
  append(buffer, size, &used, "  HIL sensor_imu received: %llu\n", u(counters.hil_imu_received));
  append(buffer, size, &used, "  IMU updates published: %llu\n", u(counters.imu_published));
  append_vector(buffer, size, &used, "accel", current.imu_received, current.accel_FRD_m_s2);
  append_vector(buffer, size, &used, "gyro", current.imu_received, current.gyro_FRD_rad_s);
  append(buffer, size, &used, "%s", "=== MAG/BARO Section ===\n");
  append(buffer, size, &used, "  HIL sensor_mag_baro received: %llu\n", u(counters.hil_mag_baro_received));
  append(buffer, size, &used, "  MAG updates published: %llu\n", u(counters.mag_published));
  append(buffer, size, &used, "  BARO updates published: %llu\n", u(counters.baro_published));
  return used;
}

std::string dsp_hitl_status_text(bool running, const DspHitlCounters& counters, const DspHitlCurrent& current) {
  const std::size_t length = format_dsp_hitl_status(nullptr, 0, running, counters, current);
  std::string text(length + 1, '\0');
  format_dsp_hitl_status(&text[0], text.size(), running, counters, current);
  text.resize(length);
  return text;
}

}  // namespace hitl::target
