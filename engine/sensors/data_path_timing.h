// The board's data path timing (issue 37 item 4): how late the flight stack reads each sensor
// sample on a VOXL2. The spec's path ("HITL data path"): the apps processor's HIL split publishes
// hil_sensor_imu every 4 ms (HIL_IMU_PUBLISH_INTERVAL_US = 4000) and hil_sensor_mag_baro every
// 10 ms, each time the newest it holds; the DSP's dsp_hitl polls every 4 ms (a 4 ms usleep) and
// republishes what is new as sensor_accel/gyro/mag/baro with fresh DSP timestamps. Neither clock
// is tied to the simulator's, so a sample waits a uniform part of the publish interval, then a
// uniform part of the poll interval: 0 to 8 ms for the IMU (4 ms on average), 0 to 14 ms for the
// magnetometer and barometer (7 ms), and PX4 takes it as taken when the DSP republished it.
//
// With the model on, the session sends at each step the IMU as it was that long before (linear
// between the two samples around that time) and a magnetometer or barometer sample once its delay
// has passed, so a lockstep flight stack (PX4 SITL, hitl target) sees the board's sample-to-use
// delay. The phases are drawn per sample from their own seeded stream: the same seed, the same
// delays. Off, the frame passes unchanged.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <string>
#include <string_view>

#include "engine/model/random_stream.h"
#include "engine/sensors/samples.h"
#include "engine/sensors/sensor_frame.h"

namespace hitl::sensors {

/// The intervals of the board's path, seconds (the spec's figures for the VOXL2).
struct DataPathTimingConfig {
  double imu_publish_interval_s = 0.004;       ///< the split's hil_sensor_imu (HIL_IMU_PUBLISH_INTERVAL_US)
  double mag_baro_publish_interval_s = 0.010;  ///< the split's hil_sensor_mag_baro
  double dsp_poll_interval_s = 0.004;          ///< dsp_hitl's poll (250 Hz, a 4 ms usleep)
};

/// The figures of the delays applied, since the start.
struct DataPathTimingFigures {
  uint64_t imu_samples = 0;
  double imu_delay_mean_s = 0;
  double imu_delay_max_s = 0;
  uint64_t mag_baro_samples = 0;  ///< magnetometer and barometer samples delivered
  double mag_baro_delay_mean_s = 0;
  double mag_baro_delay_max_s = 0;
};

class DataPathTiming {
 public:
  DataPathTiming(const DataPathTimingConfig& config, std::uint64_t seed);
  /// Replaces `frame`'s IMU, magnetometer and barometer samples by what the board's path delivers
  /// at `now_s` (the step's simulated time). GPS, units and truth pass unchanged.
  void apply(SensorFrame& frame, double now_s);
  /// Back to the start (a reset run repeats its delays).
  void reset();
  const DataPathTimingFigures& figures() const { return figures_; }

 private:
  template <typename Sample>
  struct Pending {
    Sample sample;
    double due_s = 0;
  };
  /// The IMU at `t_s`, linear between the two held samples around it (the oldest before them).
  ImuSample imu_at(double t_s) const;
  double delay_s(double publish_interval_s);
  template <typename Sample>
  std::optional<Sample> take_due(std::deque<Pending<Sample>>& queue, double now_s);

  DataPathTimingConfig config_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  std::deque<ImuSample> imu_history_;  ///< bounded: the samples of the last max delay and one more
  std::deque<Pending<MagSample>> mag_queue_;
  std::deque<Pending<BaroSample>> baro_queue_;
  DataPathTimingFigures figures_;
};

/// The names --board-timing takes, the one place they are listed: "none" (no delay) and "voxl2".
inline constexpr std::array<std::string_view, 2> kBoardTimingModels = {"none", "voxl2"};
/// "none, voxl2": the names for a message or a help text.
std::string board_timing_model_list();
/// The named models for --board-timing: "voxl2" (the spec's intervals); nullopt for "none" and any
/// name not in kBoardTimingModels.
std::optional<DataPathTimingConfig> data_path_timing_model(const std::string& name);

}  // namespace hitl::sensors
