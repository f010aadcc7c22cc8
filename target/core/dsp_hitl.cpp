#include "target/core/dsp_hitl.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/contract/device_ids.h"
#include "base/contract/dsp_hitl_status.h"

namespace hitl::target {

namespace {

bool finite3(const float (&v)[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

void copy3(const float (&from)[3], float (&to)[3]) { std::copy(from, from + 3, to); }

/// Strictly increasing publication times per sensor; the very first may be at any time.
bool advances(bool published_once, uint64_t last_us, uint64_t now_us) { return !published_once || now_us > last_us; }

}  // namespace

DspHitl::DspHitl() : imu_temperature_degC_(std::numeric_limits<float>::quiet_NaN()) {}

void DspHitl::stop() { running_ = false; }

std::optional<DspImuSamples> DspHitl::on_imu(const HilSensorImu& msg, uint64_t now_us) {
  if (!running_) return std::nullopt;
  ++counters_.hil_imu_received;
  copy3(msg.accelerometer_m_s2, current_.accel_FRD_m_s2);
  copy3(msg.gyroscope_rad_s, current_.gyro_FRD_rad_s);
  current_.imu_received = true;
  if (std::isfinite(msg.temperature)) imu_temperature_degC_ = msg.temperature;

  if (!finite3(msg.accelerometer_m_s2) || !finite3(msg.gyroscope_rad_s)) {
    ++counters_.not_finite;
    return std::nullopt;
  }
  if (!advances(imu_published_once_, last_imu_publish_us_, now_us)) {
    ++counters_.time_not_advanced;
    return std::nullopt;
  }

  DspImuSamples out;
  out.accel.timestamp_us = now_us;
  out.accel.timestamp_sample_us = now_us;
  out.accel.device_id = kDeviceIdImu;
  copy3(msg.accelerometer_m_s2, out.accel.accel_FRD_m_s2);
  out.accel.temperature_degC = imu_temperature_degC_;
  out.gyro.timestamp_us = now_us;
  out.gyro.timestamp_sample_us = now_us;
  out.gyro.device_id = kDeviceIdImu;
  copy3(msg.gyroscope_rad_s, out.gyro.gyro_FRD_rad_s);
  out.gyro.temperature_degC = imu_temperature_degC_;

  last_imu_publish_us_ = now_us;
  imu_published_once_ = true;
  ++counters_.imu_published;
  return out;
}

DspMagBaroSamples DspHitl::on_mag_baro(const HilSensorMagBaro& msg, uint64_t now_us) {
  DspMagBaroSamples out;
  if (!running_) return out;
  ++counters_.hil_mag_baro_received;

  if ((msg.fields_updated & HilSensorMagBaro::FIELD_MAG) != 0) {
    if (!finite3(msg.magnetometer_ga)) {
      ++counters_.not_finite;
    } else if (!advances(mag_published_once_, last_mag_publish_us_, now_us)) {
      ++counters_.time_not_advanced;
    } else {
      SensorMag mag;
      mag.timestamp_us = now_us;
      mag.timestamp_sample_us = now_us;
      mag.device_id = kDeviceIdMag;
      copy3(msg.magnetometer_ga, mag.mag_FRD_gauss);
      mag.temperature_degC = msg.temperature;
      out.mag = mag;
      last_mag_publish_us_ = now_us;
      mag_published_once_ = true;
      ++counters_.mag_published;
    }
  }

  if ((msg.fields_updated & HilSensorMagBaro::FIELD_BARO) != 0) {
    if (!std::isfinite(msg.pressure_pa)) {
      ++counters_.not_finite;
    } else if (!advances(baro_published_once_, last_baro_publish_us_, now_us)) {
      ++counters_.time_not_advanced;
    } else {
      SensorBaro baro;
      baro.timestamp_us = now_us;
      baro.timestamp_sample_us = now_us;
      baro.device_id = kDeviceIdBaro;
      baro.pressure_Pa = msg.pressure_pa;
      baro.temperature_degC = std::isfinite(msg.temperature) ? msg.temperature : kBaroTemperatureDefault_degC;
      out.baro = baro;
      last_baro_publish_us_ = now_us;
      baro_published_once_ = true;
      ++counters_.baro_published;
    }
  }
  return out;
}

std::string DspHitl::status_text() const { return dsp_hitl_status_text(running_, counters_, current_); }

std::size_t DspHitl::format_status(char* buffer, std::size_t size) const {
  return format_dsp_hitl_status(buffer, size, running_, counters_, current_);
}

}  // namespace hitl::target
