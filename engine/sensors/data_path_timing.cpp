#include "engine/sensors/data_path_timing.h"

#include <algorithm>

namespace hitl::sensors {
namespace {

constexpr const char* kStream = "data-path-timing";

void add_delay(uint64_t& count, double& mean_s, double& max_s, double delay_s) {
  ++count;
  mean_s += (delay_s - mean_s) / static_cast<double>(count);
  max_s = std::max(max_s, delay_s);
}

}  // namespace

DataPathTiming::DataPathTiming(const DataPathTimingConfig& config, std::uint64_t seed)
    : config_(config), seed_(seed), rng_(model::stream_seed(seed, kStream)) {}

void DataPathTiming::reset() {
  rng_.seed(model::stream_seed(seed_, kStream));
  imu_history_.clear();
  mag_queue_.clear();
  baro_queue_.clear();
  figures_ = {};
}

double DataPathTiming::delay_s(double publish_interval_s) {
  // Two draws every time, so the sequence depends on the seed and the samples only.
  const double publish_wait = uniform_(rng_) * publish_interval_s;
  const double poll_wait = uniform_(rng_) * config_.dsp_poll_interval_s;
  return publish_wait + poll_wait;
}

ImuSample DataPathTiming::imu_at(double t_s) const {
  if (t_s <= imu_history_.front().time_s) return imu_history_.front();
  for (std::size_t i = imu_history_.size() - 1; i > 0; --i) {
    const ImuSample& a = imu_history_[i - 1];
    const ImuSample& b = imu_history_[i];
    if (a.time_s <= t_s) {
      const double span_s = b.time_s - a.time_s;
      const double w = span_s > 0 ? std::clamp((t_s - a.time_s) / span_s, 0.0, 1.0) : 1.0;
      ImuSample out = a;
      out.time_s = t_s;
      out.accel_FRD_m_s2 = a.accel_FRD_m_s2 + w * (b.accel_FRD_m_s2 - a.accel_FRD_m_s2);
      out.gyro_FRD_rad_s = a.gyro_FRD_rad_s + w * (b.gyro_FRD_rad_s - a.gyro_FRD_rad_s);
      out.temperature_degC = a.temperature_degC + w * (b.temperature_degC - a.temperature_degC);
      return out;
    }
  }
  return imu_history_.front();
}

template <typename Sample>
std::optional<Sample> DataPathTiming::take_due(std::deque<Pending<Sample>>& queue, double now_s) {
  // The split publishes the newest it holds: of several due samples the newest goes out.
  std::optional<Sample> out;
  while (!queue.empty() && queue.front().due_s <= now_s + 1e-9) {
    out = queue.front().sample;
    queue.pop_front();
  }
  if (out) add_delay(figures_.mag_baro_samples, figures_.mag_baro_delay_mean_s, figures_.mag_baro_delay_max_s, now_s - out->time_s);
  return out;
}

void DataPathTiming::apply(SensorFrame& frame, double now_s) {
  if (frame.imu) {
    imu_history_.push_back(*frame.imu);
    const double delay = delay_s(config_.imu_publish_interval_s);
    frame.imu = imu_at(now_s - delay);
    add_delay(figures_.imu_samples, figures_.imu_delay_mean_s, figures_.imu_delay_max_s, now_s - frame.imu->time_s);
    // Keep what a later delay can still reach: samples since now - the longest delay, and one before.
    const double oldest_needed_s = now_s - config_.imu_publish_interval_s - config_.dsp_poll_interval_s;
    while (imu_history_.size() > 2 && imu_history_[1].time_s <= oldest_needed_s) imu_history_.pop_front();
  }
  if (frame.mag) mag_queue_.push_back({*frame.mag, frame.mag->time_s + delay_s(config_.mag_baro_publish_interval_s)});
  if (frame.baro) baro_queue_.push_back({*frame.baro, frame.baro->time_s + delay_s(config_.mag_baro_publish_interval_s)});
  // Bounded whatever the rates: a sample is due within one publish and one poll interval.
  constexpr std::size_t kMaxQueued = 64;
  while (mag_queue_.size() > kMaxQueued) mag_queue_.pop_front();
  while (baro_queue_.size() > kMaxQueued) baro_queue_.pop_front();
  frame.mag = take_due(mag_queue_, now_s);
  frame.baro = take_due(baro_queue_, now_s);
}

std::string board_timing_model_list() {
  std::string out;
  for (const std::string_view name : kBoardTimingModels) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

std::optional<DataPathTimingConfig> data_path_timing_model(const std::string& name) {
  if (name == "voxl2") return DataPathTimingConfig{};
  return std::nullopt;
}

}  // namespace hitl::sensors
