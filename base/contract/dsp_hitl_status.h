// The text of `dsp_hitl status`, exactly the spec's format ("Verify"), one line each, '\n'-ended:
//
//   Running: yes
//   === IMU Section ===
//     HIL sensor_imu received: 12453
//     IMU updates published: 12450
//     Current accel (x,y,z): -0.257, 0.151, -9.859
//     Current gyro (x,y,z): -0.006, -0.001, 0.000
//   === MAG/BARO Section ===
//     HIL sensor_mag_baro received: 4980
//     MAG updates published: 4975
//     BARO updates published: 995
//
// "Running: no" when stopped. Values with 3 decimals ("%.3f"; a value that rounds to zero prints
// "0.000", never "-0.000"; NaN prints "nan"). Before the first hil_sensor_imu the two "Current"
// lines read "Current accel (x,y,z): no data" and "Current gyro (x,y,z): no data".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace hitl::target {

/// The counters of `dsp_hitl status`, plus the reasons a received sample was not published.
struct DspHitlCounters {
  uint64_t hil_imu_received = 0;       ///< "HIL sensor_imu received"
  uint64_t imu_published = 0;          ///< "IMU updates published" (accel + gyro pairs)
  uint64_t hil_mag_baro_received = 0;  ///< "HIL sensor_mag_baro received"
  uint64_t mag_published = 0;          ///< "MAG updates published"
  uint64_t baro_published = 0;         ///< "BARO updates published"
  uint64_t not_finite = 0;             ///< samples dropped for NaN/Inf values
  uint64_t time_not_advanced = 0;      ///< samples dropped because now_us did not advance
};

/// What status shows as "Current accel/gyro" (latest received, published or not).
struct DspHitlCurrent {
  bool imu_received = false;           ///< false before the first hil_sensor_imu
  float accel_FRD_m_s2[3] = {};
  float gyro_FRD_rad_s[3] = {};
};


/// The labels of the five counters in the text, the one spelling formatter and parser share.
namespace dsp_hitl_label {
inline constexpr const char* kImuReceived = "HIL sensor_imu received";
inline constexpr const char* kImuPublished = "IMU updates published";
inline constexpr const char* kMagBaroReceived = "HIL sensor_mag_baro received";
inline constexpr const char* kMagPublished = "MAG updates published";
inline constexpr const char* kBaroPublished = "BARO updates published";
}  // namespace dsp_hitl_label

/// Writes the status into `buffer` (always NUL-terminated when size > 0) and returns the length
/// of the whole text, like snprintf: a return >= size means it was truncated.
std::size_t format_dsp_hitl_status(char* buffer, std::size_t size, bool running, const DspHitlCounters& counters,
                                   const DspHitlCurrent& current);

/// The same as a string.
std::string dsp_hitl_status_text(bool running, const DspHitlCounters& counters, const DspHitlCurrent& current);

/// What a host reads back from the status text (the shell's output of `qshell dsp_hitl status`).
struct DspHitlStatusReport {
  bool running = false;
  DspHitlCounters counters;  ///< the five counters of the text; the drop reasons are not in it (0)
  DspHitlCurrent current;    ///< imu_received false when the text says "no data"
};

/// Reads the status text back. Tolerates '\r', leading and trailing text around each line (a
/// shell's log prefixes) and lines it does not know; needs "Running:" and all five counters.
/// Returns false with `*error` naming the first missing or malformed line.
bool parse_dsp_hitl_status(const std::string& text, DspHitlStatusReport* report, std::string* error);

}  // namespace hitl::target
