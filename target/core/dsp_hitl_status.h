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
#include <string>

namespace hitl::target {

struct DspHitlCounters;
struct DspHitlCurrent;

/// Writes the status into `buffer` (always NUL-terminated when size > 0) and returns the length
/// of the whole text, like snprintf: a return >= size means it was truncated.
std::size_t format_dsp_hitl_status(char* buffer, std::size_t size, bool running, const DspHitlCounters& counters,
                                   const DspHitlCurrent& current);

/// The same as a string.
std::string dsp_hitl_status_text(bool running, const DspHitlCounters& counters, const DspHitlCurrent& current);

}  // namespace hitl::target
