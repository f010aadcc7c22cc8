// The apps processor's HIL split (spec: MavlinkReceiver, "Data Flow Rates"): HIL_SENSOR messages
// in, two rate-decoupled uORB topics out, plus the simulated battery.
//
//   hil_sensor_imu       every 4000 us (HIL_IMU_PUBLISH_INTERVAL_US) with the LATEST accel and
//                        gyro. When no new IMU data arrived since the previous publication the
//                        latest values are published again (counted in imu_repeated), so a late
//                        host does not leave a hole in the DSP's 250 Hz stream; two arrivals
//                        within one period keep only the later (counted in imu_overwritten). The
//                        grid starts imu_phase_us (half a period) after the arrival that starts
//                        the stream, so a 250 Hz host's arrivals sit mid-period: host jitter
//                        below +-2 ms then neither repeats nor drops a sample, at the cost of
//                        about 2 ms of added latency.
//   hil_sensor_mag_baro  every 10000 us, ALWAYS (100 Hz batched, also with fields_updated 0: the
//                        spec's counters have sensor_mag_baro received = 0.4 x sensor_imu
//                        received, i.e. 100 Hz against 250 Hz). FIELD_MAG is set only when a
//                        complete mag group (0x1C0) arrived since the previous publication,
//                        FIELD_BARO only for a complete baro group (0x1A00).
//   battery_status       every 100000 us (10 Hz), the constant simulated battery.
//
// Everything stops when the host goes quiet: a stream is published only while its data are at
// most hold_limit_us old (IMU: the last accel/gyro group; mag/baro and battery: the last
// HIL_SENSOR of any content; battery publication thus follows HIL_SENSOR as in PX4, where
// battery and mag/baro time out when HIL_SENSOR stops). A stream that resumes restarts its period
// at the arrival, so the first publication after a gap is immediate (IMU: after imu_phase_us).
//
// Arrival stamps: the board stamps on arrival (`now_us` of on_hil_sensor); HIL_SENSOR.time_usec
// and .id are ignored. IMU publication starts once both an accel and a gyro group have been
// received. Values never received are NaN (mag, pressure, temperature). Pressure hPa -> Pa.
// Groups with only some of their bits set are ignored (PX4 does the same) and counted.
//
// Driven by the caller's clock: on_hil_sensor() when a message arrives, poll() whenever
// convenient (at least every 4 ms; next_due_us() says when something becomes due, poll_timeout_ms()
// how long a receive loop such as PX4's MavlinkReceiver may block until then).
#pragma once

#include <cstdint>
#include <optional>

#include "base/contract/data_rates.h"
#include "target/core/hil_inputs.h"
#include "target/core/hil_uorb_messages.h"
#include "target/core/periodic_schedule.h"
#include "target/core/px4_topics.h"
#include "target/core/simulated_battery.h"

namespace hitl::target {

/// HIL_SENSOR.abs_pressure (hPa) -> hil_sensor_mag_baro.pressure_pa.
constexpr float pressure_Pa_from_hPa(float pressure_hPa) { return pressure_hPa * 100.0F; }

struct HilSplitConfig {
  uint64_t imu_period_us = kHilImuPublishPeriod_us;
  uint64_t imu_phase_us = 2000;        ///< first IMU publication this long after the stream starts
  uint64_t mag_baro_period_us = kHilMagBaroPublishPeriod_us;
  uint64_t battery_period_us = kSimBatteryPeriod_us;
  /// A stream stops when its data are older than this (25 IMU periods: far below the ~100 equal
  /// values after which PX4's sensor validator calls a sensor stale).
  uint64_t hold_limit_us = 100000;
};

struct HilSplitCounters {
  uint64_t hil_sensor_received = 0;   ///< on_hil_sensor calls
  uint64_t accel_received = 0;        ///< complete accel groups (0x007)
  uint64_t gyro_received = 0;         ///< complete gyro groups (0x038)
  uint64_t mag_received = 0;          ///< complete mag groups (0x1C0)
  uint64_t baro_received = 0;         ///< complete baro groups (0x1A00)
  uint64_t partial_groups = 0;        ///< groups with some but not all bits set (ignored)
  uint64_t imu_published = 0;         ///< hil_sensor_imu publications
  uint64_t imu_repeated = 0;          ///< ... of which without new accel/gyro since the previous
  uint64_t imu_overwritten = 0;       ///< IMU arrivals replaced by a later one before publication
  uint64_t mag_baro_published = 0;    ///< hil_sensor_mag_baro publications (any fields_updated)
  uint64_t mag_published = 0;         ///< ... with FIELD_MAG
  uint64_t baro_published = 0;        ///< ... with FIELD_BARO
  uint64_t mag_overwritten = 0;       ///< mag groups replaced before publication
  uint64_t baro_overwritten = 0;      ///< baro groups replaced before publication
  uint64_t battery_published = 0;
  uint64_t resyncs = 0;               ///< periods re-anchored because poll() came over a period late
};

/// What poll() found due; each present member is to be published now.
struct HilSplitOutput {
  std::optional<HilSensorImu> imu;
  std::optional<HilSensorMagBaro> mag_baro;
  std::optional<BatteryStatus> battery;
  bool empty() const { return !imu && !mag_baro && !battery; }
};

class HilSplit {
 public:
  explicit HilSplit(const HilSplitConfig& config = HilSplitConfig{});

  /// Takes one decoded HIL_SENSOR that arrived at `now_us` (board clock, microseconds).
  void on_hil_sensor(const HilSensorInput& msg, uint64_t now_us);
  /// Returns what is due at `now_us`; `now_us` must not go backwards.
  HilSplitOutput poll(uint64_t now_us);

  /// The earliest time at which poll() may return something; UINT64_MAX when nothing is live.
  uint64_t next_due_us() const;
  /// How long a receive loop may block (poll(2)'s timeout, whole ms) before it must call poll():
  /// the time to next_due_us() rounded up, 0 when something is due, at most `max_timeout_ms`.
  /// Rounding up makes a publication at most 1 ms late rather than waking the loop early for nothing.
  int poll_timeout_ms(uint64_t now_us, int max_timeout_ms) const;
  HilSplitCounters counters() const;
  const HilSplitConfig& config() const { return config_; }

 private:
  bool live(bool received, uint64_t last_arrival_us, uint64_t now_us) const;

  HilSplitConfig config_;
  PeriodicSchedule imu_schedule_;
  PeriodicSchedule mag_baro_schedule_;
  PeriodicSchedule battery_schedule_;
  HilSplitCounters counters_;

  // Latest values (NaN until received).
  float accel_FRD_m_s2_[3];
  float gyro_FRD_rad_s_[3];
  float mag_FRD_gauss_[3];
  float pressure_Pa_;
  float temperature_degC_;

  bool any_received_ = false;    ///< a HIL_SENSOR arrived at least once
  bool accel_seen_ = false;
  bool gyro_seen_ = false;
  uint64_t last_arrival_us_ = 0;      ///< last HIL_SENSOR of any content
  uint64_t last_imu_arrival_us_ = 0;  ///< last complete accel or gyro group
  bool imu_new_ = false;         ///< accel/gyro arrived since the last hil_sensor_imu
  bool mag_new_ = false;         ///< mag group arrived since the last hil_sensor_mag_baro
  bool baro_new_ = false;        ///< baro group arrived since the last hil_sensor_mag_baro
};

}  // namespace hitl::target
