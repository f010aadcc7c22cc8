// Sample scheduling on absolute due times: sample k of a sensor at rate r is due at k / r, so the
// long-run rate is exact even when the period is not a multiple of the physics step (GPS 30 Hz
// against 4 ms steps). A sensor asked at time t is due when t has reached its next due time; one
// sample is then taken and the next due time is the first k / r after t.
#pragma once

#include <cstdint>

namespace hitl::sensors {

class PeriodicSchedule {
 public:
  explicit PeriodicSchedule(double rate_hz) : rate_hz_(rate_hz) {}
  /// True when a sample is due at t (and consumes it).
  bool due(double t_s);
  double next_due_s() const { return static_cast<double>(next_index_) / rate_hz_; }
  void reset() { next_index_ = 0; }

 private:
  double rate_hz_;
  std::uint64_t next_index_ = 0;
};

/// Which sensors to sample after the step that ended at t.
struct DueSensors {
  bool imu = false;
  bool mag = false;
  bool baro = false;
  bool gps = false;
};

class SensorScheduler {
 public:
  SensorScheduler(double imu_rate_hz, double mag_rate_hz, double baro_rate_hz, double gps_rate_hz)
      : imu_(imu_rate_hz), mag_(mag_rate_hz), baro_(baro_rate_hz), gps_(gps_rate_hz), first_s_(1.0 / imu_rate_hz) {}
  /// Nothing is due before one IMU period has passed, so the first samples go out at the first IMU
  /// period (4000 us) whatever the physics step: a 2 ms step used to send one at 2000 us first.
  DueSensors due(double t_s) {
    if (t_s + 1e-9 < first_s_) return {};
    return {imu_.due(t_s), mag_.due(t_s), baro_.due(t_s), gps_.due(t_s)};
  }
  void reset() {
    imu_.reset();
    mag_.reset();
    baro_.reset();
    gps_.reset();
  }

 private:
  PeriodicSchedule imu_, mag_, baro_, gps_;
  double first_s_;
};

}  // namespace hitl::sensors
