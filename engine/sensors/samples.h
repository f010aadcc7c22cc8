// What the sensors return: wire-ready SI units in body FRD / world NED (the codec turns these into
// MAVLink fields: Pa -> hPa, deg -> degE7, m -> mm, m/s -> cm/s, ...).
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hitl::sensors {

struct ImuSample {
  double time_s = 0.0;
  Eigen::Vector3d accel_FRD_m_s2 = Eigen::Vector3d::Zero();  ///< specific force (level at rest: z = -g)
  Eigen::Vector3d gyro_FRD_rad_s = Eigen::Vector3d::Zero();
  double temperature_degC = 0.0;
};

struct MagSample {
  double time_s = 0.0;
  Eigen::Vector3d mag_FRD_gauss = Eigen::Vector3d::Zero();
};

struct BaroSample {
  double time_s = 0.0;
  double pressure_Pa = 0.0;     ///< absolute pressure (HIL_SENSOR carries hPa)
  double temperature_degC = 0.0;
  double pressure_alt_m = 0.0;  ///< ISA altitude of the measured pressure
};

struct GpsSample {
  double time_s = 0.0;  ///< when the fix was taken (earlier than now when delayed)
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;  ///< MSL (PX4 uses it as ellipsoid height too)
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  double ground_speed_m_s = 0.0;
  double course_over_ground_deg = 0.0;  ///< 0..360, from north towards east
  double eph_m = 0.0;
  double epv_m = 0.0;
  std::uint8_t fix_type = 3;  ///< 3 = 3D fix
  std::uint8_t satellites = 0;
};

/// Time since a sensor's previous sample (updates `last_t_s`); the nominal period for the first one.
inline double sample_interval_s(double& last_t_s, double t_s, double rate_hz) {
  const double dt_s = (last_t_s < 0.0 || t_s <= last_t_s) ? 1.0 / rate_hz : t_s - last_t_s;
  last_t_s = t_s;
  return dt_s;
}

/// Exact state for ODOMETRY and for comparing an estimate against truth.
struct GroundTruth {
  double time_s = 0.0;
  Eigen::Vector3d p_NED_m = Eigen::Vector3d::Zero();  ///< base origin from home (ground), NED
  Eigen::Quaterniond q_FRD_to_NED = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_FRD_m_s = Eigen::Vector3d::Zero();  ///< ODOMETRY velocities are in the child frame
  Eigen::Vector3d w_FRD_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_FRD_m_s2 = Eigen::Vector3d::Zero();  ///< specific force at the base origin, noise-free
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;
};

}  // namespace hitl::sensors
