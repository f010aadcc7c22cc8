// The simulator's statement of its IMU's noise, one STATUSTEXT at the start of a session (so that a
// recording carries what the IMU was set to, and `hitl report` can mark it on the Allan deviation):
//   "imu noise (profile icm-42688-p): gyro N 4.8869e-05 rad/s/sqrt(Hz) B 0 rad/s, accel N 6.8647e-04 m/s^2/sqrt(Hz) B 0 m/s^2"
// N the white noise density, B the bias instability (IEEE 952), the values the session runs with (a
// vehicle file's keys over its profile); "(profile NAME)" only when the profile is known.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace hitl::telemetry {

struct ImuNoiseFigures {
  std::string profile;  ///< "icm-42688-p" ("" : not said)
  double gyro_noise_density = 0.0;    ///< rad/s/sqrt(Hz)
  double gyro_bias_instability = 0.0;  ///< rad/s
  double accel_noise_density = 0.0;    ///< m/s^2/sqrt(Hz)
  double accel_bias_instability = 0.0;  ///< m/s^2
};

std::string imu_noise_statement(const ImuNoiseFigures& figures);
/// The figures of a statement; nullopt for any other text (a profile name is at most 64 characters
/// of [a-z0-9.-_], every figure in [0, 1e6]).
std::optional<ImuNoiseFigures> parse_imu_noise_statement(std::string_view text);

}  // namespace hitl::telemetry
