// What the flight core eats: sensor samples, sticks and commands as plain values in body FRD /
// world NED SI units, each stamped by the caller's clock in microseconds. The emulator fills these
// from HIL_SENSOR / HIL_GPS / RC_CHANNELS_OVERRIDE; the in-process tests fill them from the engine.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Core>

namespace hitl::flight {

struct ImuSample {
  std::uint64_t time_us = 0;
  Eigen::Vector3d accel_FRD_m_s2 = Eigen::Vector3d::Zero();  ///< specific force; level at rest (0, 0, -g)
  Eigen::Vector3d gyro_FRD_rad_s = Eigen::Vector3d::Zero();
};

struct MagSample {
  std::uint64_t time_us = 0;
  Eigen::Vector3d mag_FRD_gauss = Eigen::Vector3d::Zero();
};

struct BaroSample {
  std::uint64_t time_us = 0;
  double pressure_Pa = 0.0;  ///< absolute (HIL_SENSOR carries hPa: multiply by 100)
  double temperature_degC = 15.0;
};

struct GpsSample {
  std::uint64_t time_us = 0;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_msl_m = 0.0;
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  double eph_m = 99.0;
  double epv_m = 99.0;
  std::uint8_t fix_type = 0;  ///< GPS_FIX_TYPE: 0-1 no fix, 2 2D, 3 3D, ...
  std::uint8_t satellites = 0;
};

/// Sticks with PX4's ManualControlSetpoint meaning (mode 2 transmitter):
///   roll  -1..1  +1 = move right (right side down)
///   pitch -1..1  +1 = move forward (nose down)
///   yaw   -1..1  +1 = turn right (clockwise seen from above)
///   throttle 0..1, 0.5 = centre (position mode: hold altitude), 1 = climb at full rate
struct StickInput {
  std::uint64_t time_us = 0;
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;
  double throttle = 0.5;
};

/// MAV_CMD_NAV_TAKEOFF: altitude AMSL (param 7) or relative to home; NaN = MIS_TAKEOFF_ALT above home.
struct TakeoffRequest {
  double altitude_m = std::numeric_limits<double>::quiet_NaN();
  bool relative_to_home = false;
};

}  // namespace hitl::flight
