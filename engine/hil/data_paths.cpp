#include "engine/hil/data_paths.h"

#include "base/mavlink/messages.h"

namespace hitl::hil {
namespace {
// Positions in paths_: the fixed ones first, ODOMETRY (when on) before the actuators.
constexpr std::size_t kImu = 0, kMag = 1, kBaro = 2, kGps = 3;
}  // namespace

DataPaths::DataPaths(const SessionConfig& config, bool lockstep) {
  const auto& sensors = config.vehicle.sensors;
  auto add = [&](const char* name, std::string_view message, bool outgoing, double rate_hz, bool scales) {
    Path p;
    p.info.name = name;
    p.info.message = std::string(message);
    p.info.outgoing = outgoing;
    p.base_rate_hz = rate_hz;
    p.scales_with_pace = scales;
    paths_.push_back(std::move(p));
  };
  add("IMU", mavlink::msg::HilSensor::kName, true, sensors.imu.rate_hz, true);
  add("mag", mavlink::msg::HilSensor::kName, true, sensors.mag.rate_hz, true);
  add("baro", mavlink::msg::HilSensor::kName, true, sensors.baro.rate_hz, true);
  add("GPS", mavlink::msg::HilGps::kName, true, sensors.gps.rate_hz, true);
  if (config.vio) {
    odometry_ = paths_.size();
    add("ODOMETRY", mavlink::msg::Odometry::kName, true, config.vio_rate_hz, true);
  }
  // Lockstep: one answer per sensor message, so the IMU's pace; otherwise the board's own clock.
  add("actuators", mavlink::msg::HilActuatorControls::kName, false, lockstep ? sensors.imu.rate_hz : kActuatorStreamRate_hz,
      lockstep);
  for (auto& p : paths_) p.info.expected_hz = p.base_rate_hz;
}

void DataPaths::on_hil_sensor(bool imu, bool mag, bool baro, double now_s) {
  if (imu) path(kImu).meter.arrival(now_s);
  if (mag) path(kMag).meter.arrival(now_s);
  if (baro) path(kBaro).meter.arrival(now_s);
}

void DataPaths::on_hil_gps(double now_s) { path(kGps).meter.arrival(now_s); }

void DataPaths::on_odometry(double now_s) {
  if (odometry_) path(*odometry_).meter.arrival(now_s);
}

void DataPaths::on_stack_frame(const mavlink::Frame& frame, double now_s) {
  stack_sequences_[{frame.sysid, frame.compid}].observe(frame.seq);
  if (frame.msgid == mavlink::msg::HilActuatorControls::kId) paths_.back().meter.arrival(now_s);
}

void DataPaths::roll(double now_s, double pace) {
  for (auto& p : paths_) {
    p.meter.roll(now_s);
    p.info.expected_hz = p.scales_with_pace ? p.base_rate_hz * pace : p.base_rate_hz;
  }
  uint64_t received = 0, lost = 0;
  for (const auto& [key, tracker] : stack_sequences_) {
    received += tracker.stats().received;
    lost += tracker.stats().lost;
  }
  const uint64_t window_received = received - window_start_received_;
  const uint64_t window_lost = lost - window_start_lost_;
  if (window_received + window_lost > 0)
    last_loss_pct_ = 100.0 * static_cast<double>(window_lost) / static_cast<double>(window_received + window_lost);
  else
    last_loss_pct_.reset();
  window_start_received_ = received;
  window_start_lost_ = lost;
}

std::vector<DataPathStats> DataPaths::stats(double now_s) const {
  std::vector<DataPathStats> out;
  out.reserve(paths_.size());
  for (const auto& p : paths_) {
    DataPathStats s = p.info;
    s.stats = p.meter.stats(now_s);
    if (!s.outgoing) s.loss_pct = last_loss_pct_;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace hitl::hil
