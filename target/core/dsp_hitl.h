// The DSP side (spec: dsp_hitl Driver): takes each new hil_sensor_imu / hil_sensor_mag_baro that
// MUORB delivered and republishes it as PX4's native sensor topics with fresh DSP timestamps
// (timestamp = timestamp_sample = `now_us`, the DSP clock at republication):
//   hil_sensor_imu                  -> sensor_accel + sensor_gyro (kDeviceIdImu)
//   hil_sensor_mag_baro, FIELD_MAG  -> sensor_mag  (kDeviceIdMag)
//   hil_sensor_mag_baro, FIELD_BARO -> sensor_baro (kDeviceIdBaro)
// A sample is published only when its values are finite and `now_us` is later than the previous
// publication of that sensor (PX4's consumers need strictly increasing timestamps); otherwise it
// is received but not published (the spec's status shows published below received). IMU
// temperature is the last finite one received (NaN before); a non-finite baro temperature becomes
// 15 degC (ISA sea level); mag temperature passes through.
//
// The PX4 module polls both topics every 4 ms (usleep 4000) and calls on_imu / on_mag_baro for
// each update; the emulator calls them as messages arrive. Between start() and stop() only:
// while stopped, input is ignored (the module's task is not running). stop() keeps counters and
// current values; clear_counters() is the module's "clear" verb.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "base/contract/dsp_hitl_status.h"
#include "target/core/hil_uorb_messages.h"
#include "target/core/px4_topics.h"

namespace hitl::target {

/// What on_imu publishes: one accel and one gyro sample, same timestamps.
struct DspImuSamples {
  SensorAccel accel;
  SensorGyro gyro;
};

/// What on_mag_baro publishes: each present member is to be published.
struct DspMagBaroSamples {
  std::optional<SensorMag> mag;
  std::optional<SensorBaro> baro;
};

class DspHitl {
 public:
  static constexpr float kBaroTemperatureDefault_degC = 15.0F;

  DspHitl();
  void start() { running_ = true; }
  /// Stops republishing; counters and current values stay until clear_counters().
  void stop();
  bool running() const { return running_; }

  /// One new hil_sensor_imu seen at DSP time `now_us`; the samples to publish, if any.
  std::optional<DspImuSamples> on_imu(const HilSensorImu& msg, uint64_t now_us);
  /// One new hil_sensor_mag_baro seen at DSP time `now_us`; mag and baro by fields_updated bit.
  DspMagBaroSamples on_mag_baro(const HilSensorMagBaro& msg, uint64_t now_us);

  void clear_counters() { counters_ = DspHitlCounters{}; }
  const DspHitlCounters& counters() const { return counters_; }
  const DspHitlCurrent& current() const { return current_; }

  /// `dsp_hitl status` in the spec's format (dsp_hitl_status.h), as one string.
  std::string status_text() const;
  /// The same text into `buffer` without allocating (for the DSP build); snprintf semantics.
  std::size_t format_status(char* buffer, std::size_t size) const;

 private:
  bool running_ = false;
  DspHitlCounters counters_;
  DspHitlCurrent current_;
  float imu_temperature_degC_;
  uint64_t last_imu_publish_us_ = 0;
  uint64_t last_mag_publish_us_ = 0;
  uint64_t last_baro_publish_us_ = 0;
  bool imu_published_once_ = false;
  bool mag_published_once_ = false;
  bool baro_published_once_ = false;
};

}  // namespace hitl::target
