// The MAVLink messages the simulator sends, built from the engine's samples (already in body FRD /
// world NED, SI units): HIL_SENSOR with fields_updated naming exactly what was sampled this step,
// HIL_GPS, ODOMETRY from ground truth, HIL_STATE_QUATERNION.
#pragma once

#include "base/mavlink/messages.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl::hil {

/// HIL_SENSOR for one step: IMU (accel + gyro bits) when sampled, mag bits with a mag sample, the
/// baro group (abs_pressure, pressure_alt, temperature: bits 9, 11, 12 together, as PX4 reads it)
/// with a baro sample. `time_usec` is simulated time (PX4 SITL's clock; must be > 0).
mavlink::msg::HilSensor make_hil_sensor(const sensors::SensorFrame& frame, uint64_t time_usec);

/// HIL_GPS from a fix: degE7, mm, cm accuracies, cm/s velocities, cdeg course (65535 when standing).
mavlink::msg::HilGps make_hil_gps(const sensors::GpsSample& gps, uint64_t time_usec);

/// ODOMETRY from ground truth: frame_id MAV_FRAME_LOCAL_NED, child MAV_FRAME_BODY_FRD, q = FRD->NED
/// (w, x, y, z), velocities and rates in the child frame, covariance diagonals set.
mavlink::msg::Odometry make_odometry(const sensors::GroundTruth& truth, uint64_t time_usec);

/// HIL_STATE_QUATERNION (ground truth; PX4 SITL asks for it for its logs).
mavlink::msg::HilStateQuaternion make_hil_state_quaternion(const sensors::GroundTruth& truth, uint64_t time_usec);

/// Below this ground speed the course over ground is reported unknown.
inline constexpr double kCogMinSpeed_m_s = 0.2;

/// Variances hitl reports for its (exact) ground-truth odometry: small but non-zero, so EKF2's
/// external-vision fusion trusts it without dividing by zero.
inline constexpr float kOdometryPositionVariance_m2 = 1e-4f;
inline constexpr float kOdometryAttitudeVariance_rad2 = 1e-4f;
inline constexpr float kOdometryVelocityVariance_m2_s2 = 1e-4f;

}  // namespace hitl::hil
