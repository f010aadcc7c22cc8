#include "target/core/hil_split.h"

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include "base/mavlink/hil_sensor_fields.h"

namespace hitl::target {

namespace hil_sensor = mavlink::hil_sensor;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void copy3(const float (&from)[3], float (&to)[3]) { std::copy(from, from + 3, to); }

/// Counts a group whose bits are only partly set (PX4 ignores it too).
bool partial(uint32_t fields_updated, uint32_t group) {
  return (fields_updated & group) != 0 && !hil_sensor::has_group(fields_updated, group);
}

}  // namespace

HilSplit::HilSplit(const HilSplitConfig& config)
    : config_(config),
      imu_schedule_(config.imu_period_us),
      mag_baro_schedule_(config.mag_baro_period_us),
      battery_schedule_(config.battery_period_us),
      accel_FRD_m_s2_{kNaN, kNaN, kNaN},
      gyro_FRD_rad_s_{kNaN, kNaN, kNaN},
      mag_FRD_gauss_{kNaN, kNaN, kNaN},
      pressure_Pa_(kNaN),
      temperature_degC_(kNaN) {}

bool HilSplit::live(bool received, uint64_t last_arrival_us, uint64_t now_us) const {
  return received && now_us >= last_arrival_us && now_us - last_arrival_us <= config_.hold_limit_us;
}

void HilSplit::on_hil_sensor(const HilSensorInput& msg, uint64_t now_us) {
  using namespace hil_sensor;
  ++counters_.hil_sensor_received;

  const bool link_was_live = live(any_received_, last_arrival_us_, now_us);
  const bool imu_was_live = live(accel_seen_ && gyro_seen_, last_imu_arrival_us_, now_us);
  any_received_ = true;
  last_arrival_us_ = now_us;

  const uint32_t fields = msg.fields_updated;
  bool imu_arrived = false;
  if (has_group(fields, kAccel)) {
    copy3(msg.accel_FRD_m_s2, accel_FRD_m_s2_);
    accel_seen_ = true;
    imu_arrived = true;
    ++counters_.accel_received;
  }
  if (has_group(fields, kGyro)) {
    copy3(msg.gyro_FRD_rad_s, gyro_FRD_rad_s_);
    gyro_seen_ = true;
    imu_arrived = true;
    ++counters_.gyro_received;
  }
  if (imu_arrived) {
    if (imu_new_) ++counters_.imu_overwritten;
    imu_new_ = true;
    last_imu_arrival_us_ = now_us;
  }
  if (has_group(fields, kMag)) {
    if (mag_new_) ++counters_.mag_overwritten;
    copy3(msg.mag_FRD_gauss, mag_FRD_gauss_);
    mag_new_ = true;
    ++counters_.mag_received;
  }
  if (has_group(fields, kBaro)) {
    if (baro_new_) ++counters_.baro_overwritten;
    pressure_Pa_ = pressure_Pa_from_hPa(msg.abs_pressure_hPa);
    baro_new_ = true;
    ++counters_.baro_received;
  }
  if ((fields & kTemperature) != 0) temperature_degC_ = msg.temperature_degC;
  for (uint32_t group : {kAccel, kGyro, kMag, kBaro}) {
    if (partial(fields, group)) ++counters_.partial_groups;
  }

  // A stream that was quiet (or never ran) restarts its period now: mag/baro and battery publish
  // at once, the IMU half a period later (mid-period for the host's following arrivals).
  if (!link_was_live) {
    mag_baro_schedule_.start(now_us);
    battery_schedule_.start(now_us);
  }
  if (imu_arrived && accel_seen_ && gyro_seen_ && !imu_was_live) imu_schedule_.start(now_us + config_.imu_phase_us);
}

HilSplitOutput HilSplit::poll(uint64_t now_us) {
  HilSplitOutput out;

  if (imu_schedule_.due(now_us)) {
    if (!live(accel_seen_ && gyro_seen_, last_imu_arrival_us_, now_us)) {
      imu_schedule_.stop();
    } else {
      HilSensorImu imu;
      imu.timestamp = now_us;
      copy3(accel_FRD_m_s2_, imu.accelerometer_m_s2);
      copy3(gyro_FRD_rad_s_, imu.gyroscope_rad_s);
      imu.temperature = temperature_degC_;
      out.imu = imu;
      ++counters_.imu_published;
      if (!imu_new_) ++counters_.imu_repeated;
      imu_new_ = false;
      imu_schedule_.consume(now_us);
    }
  }

  const bool link_live = live(any_received_, last_arrival_us_, now_us);
  if (mag_baro_schedule_.due(now_us)) {
    if (!link_live) {
      mag_baro_schedule_.stop();
    } else {
      HilSensorMagBaro mb;
      mb.timestamp = now_us;
      copy3(mag_FRD_gauss_, mb.magnetometer_ga);
      mb.pressure_pa = pressure_Pa_;
      mb.temperature = temperature_degC_;
      mb.fields_updated = static_cast<uint8_t>((mag_new_ ? HilSensorMagBaro::FIELD_MAG : 0) |
                                               (baro_new_ ? HilSensorMagBaro::FIELD_BARO : 0));
      out.mag_baro = mb;
      ++counters_.mag_baro_published;
      if (mag_new_) ++counters_.mag_published;
      if (baro_new_) ++counters_.baro_published;
      mag_new_ = false;
      baro_new_ = false;
      mag_baro_schedule_.consume(now_us);
    }
  }

  if (battery_schedule_.due(now_us)) {
    if (!link_live) {
      battery_schedule_.stop();
    } else {
      out.battery = make_simulated_battery(now_us);
      ++counters_.battery_published;
      battery_schedule_.consume(now_us);
    }
  }
  return out;
}

uint64_t HilSplit::next_due_us() const {
  uint64_t next_us = std::numeric_limits<uint64_t>::max();
  for (const PeriodicSchedule* s : {&imu_schedule_, &mag_baro_schedule_, &battery_schedule_}) {
    if (s->running()) next_us = std::min(next_us, s->next_due_us());
  }
  return next_us;
}

int HilSplit::poll_timeout_ms(uint64_t now_us, int max_timeout_ms) const {
  const int max_ms = std::max(max_timeout_ms, 0);
  const uint64_t due_us = next_due_us();
  if (due_us <= now_us) return 0;
  const uint64_t wait_us = due_us - now_us;  // UINT64_MAX when nothing is live: no "+ 999" overflow
  const uint64_t wait_ms = wait_us / 1000 + (wait_us % 1000 != 0 ? 1 : 0);
  return wait_ms < static_cast<uint64_t>(max_ms) ? static_cast<int>(wait_ms) : max_ms;
}

HilSplitCounters HilSplit::counters() const {
  HilSplitCounters c = counters_;
  c.resyncs = imu_schedule_.resyncs() + mag_baro_schedule_.resyncs() + battery_schedule_.resyncs();
  return c;
}

}  // namespace hitl::target
