#include "engine/telemetry/imu_series.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/hil_sensor_fields.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"

namespace hitl::telemetry {

namespace msg = mavlink::msg;

Expected<ImuSeries> read_imu_series(const std::string& path, std::size_t max_samples, const ImuWindow& window) {
  const std::string name = "'" + path + "'";
  auto reader = mavlink::TlogReader::open(path, mavlink::TlogInput::FileOrPipe);
  if (!reader) return reader.error().prefixed(name + ": ");
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  ImuSeries s;
  std::optional<uint8_t> simulator_sysid;
  std::uint64_t first_usec = 0;
  std::uint64_t last_usec = 0;
  std::uint64_t frames = 0;
  bool backwards = false;
  std::uint64_t outside_window = 0;
  std::vector<std::uint64_t> times_usec;
  mavlink::TlogRecord record;
  while (reader->next(record)) {
    parser.parse_datagram(record.frame, [&](const mavlink::Frame& f) {
      ++frames;
      if (!f.is<msg::HilSensor>()) return;
      if (!simulator_sysid) simulator_sysid = f.sysid;
      if (f.sysid != *simulator_sysid) {
        ++s.other_systems;
        return;
      }
      const auto m = f.as<msg::HilSensor>();
      namespace hs = mavlink::hil_sensor;
      if (!hs::has_group(m.fields_updated, hs::kAccel) || !hs::has_group(m.fields_updated, hs::kGyro)) return;
      const double t_s = static_cast<double>(m.time_usec) * 1e-6;
      if (t_s < window.from_s || t_s > window.to_s) {
        ++outside_window;
        return;
      }
      if (s.samples >= max_samples) {
        ++s.samples_beyond_cap;
        return;
      }
      if (s.samples == 0) first_usec = m.time_usec;
      else if (m.time_usec <= last_usec) backwards = true;
      last_usec = m.time_usec;
      times_usec.push_back(m.time_usec);
      const double gyro[3] = {m.xgyro, m.ygyro, m.zgyro};
      const double accel[3] = {m.xacc, m.yacc, m.zacc};
      for (int i = 0; i < 3; ++i) {
        s.gyro_FRD_rad_s[i].push_back(gyro[i]);
        s.accel_FRD_m_s2[i].push_back(accel[i]);
      }
      ++s.samples;
    });
  }
  if (reader->stats().records == 0) return Error::input(name + " is empty");
  if (frames == 0) return Error::input(name + " is not a .tlog: no MAVLink frame behind an 8-byte timestamp");
  if (s.samples == 0 && outside_window > 0) {
    char span[96];
    if (std::isfinite(window.to_s)) std::snprintf(span, sizeof span, "%g s to %g s", window.from_s, window.to_s);
    else std::snprintf(span, sizeof span, "%g s to the end", window.from_s);
    return Error::input(name + " holds no HIL_SENSOR with accel and gyro from " + span + " of its time_usec (" +
                        std::to_string(outside_window) + " outside)");
  }
  if (s.samples == 0)
    return Error::input(name + " holds no HIL_SENSOR with accel and gyro (" + std::to_string(frames) +
                        " frames): record one with hitl sim --record FILE.tlog");
  if (s.samples < kAllanMinSamples)
    return Error::input(name + " holds " + std::to_string(s.samples) + " IMU samples; the Allan deviation needs at least " +
                        std::to_string(kAllanMinSamples));
  if (backwards || last_usec <= first_usec)
    return Error::input(name + ": HIL_SENSOR time_usec does not move forward: not one recording at a steady rate");
  s.duration_s = static_cast<double>(last_usec - first_usec) * 1e-6;
  s.rate_hz = static_cast<double>(s.samples - 1) / s.duration_s;
  const double mean_interval_usec = static_cast<double>(last_usec - first_usec) / static_cast<double>(s.samples - 1);
  for (std::size_t i = 1; i < times_usec.size(); ++i)
    if (static_cast<double>(times_usec[i] - times_usec[i - 1]) > 1.5 * mean_interval_usec) ++s.gaps;
  return s;
}


std::vector<AxisAllan> imu_allan(const ImuSeries& series) {
  std::vector<AxisAllan> out;
  static constexpr const char* kAxes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    AxisAllan a{"gyro", kAxes[i], "rad/s", overlapping_allan_deviation(series.gyro_FRD_rad_s[i], series.rate_hz), {}};
    a.fit = fit_allan(a.curve);
    out.push_back(std::move(a));
  }
  for (int i = 0; i < 3; ++i) {
    AxisAllan a{"accel", kAxes[i], "m/s^2", overlapping_allan_deviation(series.accel_FRD_m_s2[i], series.rate_hz), {}};
    a.fit = fit_allan(a.curve);
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace hitl::telemetry
