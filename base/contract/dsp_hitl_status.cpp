#include "base/contract/dsp_hitl_status.h"

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace hitl::target {

namespace {

using namespace dsp_hitl_label;
constexpr const char* kRunning = "Running";
constexpr const char* kNoData = "no data";

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
    append(buffer, size, used, "  Current %s (x,y,z): %s\n", label, kNoData);
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
  append(buffer, size, &used, "%s: %s\n", kRunning, running ? "yes" : "no");
  append(buffer, size, &used, "%s", "=== IMU Section ===\n");
  append(buffer, size, &used, "  %s: %llu\n", kImuReceived, u(counters.hil_imu_received));
  append(buffer, size, &used, "  %s: %llu\n", kImuPublished, u(counters.imu_published));
  append_vector(buffer, size, &used, "accel", current.imu_received, current.accel_FRD_m_s2);
  append_vector(buffer, size, &used, "gyro", current.imu_received, current.gyro_FRD_rad_s);
  append(buffer, size, &used, "%s", "=== MAG/BARO Section ===\n");
  append(buffer, size, &used, "  %s: %llu\n", kMagBaroReceived, u(counters.hil_mag_baro_received));
  append(buffer, size, &used, "  %s: %llu\n", kMagPublished, u(counters.mag_published));
  append(buffer, size, &used, "  %s: %llu\n", kBaroPublished, u(counters.baro_published));
  return used;
}

std::string dsp_hitl_status_text(bool running, const DspHitlCounters& counters, const DspHitlCurrent& current) {
  const std::size_t length = format_dsp_hitl_status(nullptr, 0, running, counters, current);
  std::string text(length + 1, '\0');
  format_dsp_hitl_status(&text[0], text.size(), running, counters, current);
  text.resize(length);
  return text;
}

namespace {

/// The text after "label:" on `line`, if the line carries that label.
bool value_after(const std::string& line, const char* label, std::string* value) {
  const std::string key = std::string(label) + ":";
  const std::size_t at = line.find(key);
  if (at == std::string::npos) return false;
  std::size_t begin = at + key.size();
  while (begin < line.size() && line[begin] == ' ') ++begin;
  std::size_t end = line.size();
  while (end > begin && (line[end - 1] == ' ' || line[end - 1] == '\r')) --end;
  *value = line.substr(begin, end - begin);
  return true;
}

/// A decimal counter that fills the whole value ("12453"); false for anything else.
bool parse_counter(const std::string& value, uint64_t* out) {
  if (value.empty() || value.size() > 20) return false;
  for (const char c : value)
    if (c < '0' || c > '9') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(value.c_str(), &end, 10);
  if (errno != 0 || end == nullptr || *end != '\0') return false;
  *out = static_cast<uint64_t>(n);
  return true;
}

/// "x, y, z" with three finite or "nan" floats, or "no data".
bool parse_vector(const std::string& value, bool* received, float (&v)[3]) {
  if (value == kNoData) {
    *received = false;
    return true;
  }
  const char* p = value.c_str();
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = std::strtof(p, &end);
    if (end == p) return false;
    p = end;
    while (*p == ' ') ++p;
    if (i < 2) {
      if (*p != ',') return false;
      ++p;
    }
  }
  if (*p != '\0') return false;
  *received = true;
  return true;
}

}  // namespace

bool parse_dsp_hitl_status(const std::string& text, DspHitlStatusReport* report, std::string* error) {
  DspHitlStatusReport r;
  struct Counter {
    const char* label;
    uint64_t* field;
    bool seen;
  };
  Counter counters[] = {{kImuReceived, &r.counters.hil_imu_received, false},
                        {kImuPublished, &r.counters.imu_published, false},
                        {kMagBaroReceived, &r.counters.hil_mag_baro_received, false},
                        {kMagPublished, &r.counters.mag_published, false},
                        {kBaroPublished, &r.counters.baro_published, false}};
  bool running_seen = false;
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    std::string value;
    bool matched = false;
    for (Counter& c : counters) {
      if (!value_after(line, c.label, &value)) continue;
      if (!parse_counter(value, c.field)) return fail("'" + std::string(c.label) + "': '" + value + "' is not a count");
      c.seen = true;
      matched = true;
      break;
    }
    if (matched) continue;
    if (value_after(line, kRunning, &value)) {
      if (value != "yes" && value != "no") return fail("'Running': '" + value + "' is neither yes nor no");
      r.running = value == "yes";
      running_seen = true;
    } else if (value_after(line, "Current accel (x,y,z)", &value)) {
      bool received = false;
      if (!parse_vector(value, &received, r.current.accel_FRD_m_s2)) return fail("'Current accel': '" + value + "' is not x, y, z");
      r.current.imu_received = received;
    } else if (value_after(line, "Current gyro (x,y,z)", &value)) {
      bool received = false;
      if (!parse_vector(value, &received, r.current.gyro_FRD_rad_s)) return fail("'Current gyro': '" + value + "' is not x, y, z");
    }
    if (end == text.size()) break;
  }
  if (!running_seen) return fail("no 'Running:' line: not the output of dsp_hitl status");
  for (const Counter& c : counters)
    if (!c.seen) return fail("no '" + std::string(c.label) + ":' line");
  if (report != nullptr) *report = r;
  return true;
}

}  // namespace hitl::target
