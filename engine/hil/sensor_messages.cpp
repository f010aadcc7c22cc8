#include "engine/hil/sensor_messages.h"

#include <array>
#include <cmath>

#include "base/mavlink/enums.h"
#include "base/mavlink/hil_sensor_fields.h"
#include "base/mavlink/wire_units.h"

namespace hitl::hil {
namespace {

constexpr float kGravity_m_s2 = 9.80665f;

/// A quaternion as MAVLink carries it: w, x, y, z.
std::array<float, 4> wxyz(const Eigen::Quaterniond& q) {
  return {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())};
}

// Indices of the diagonal in MAVLink's 21-element upper-right triangle of a 6x6 covariance.
constexpr int kCovarianceDiagonal[6] = {0, 6, 11, 15, 18, 20};

}  // namespace

mavlink::msg::HilSensor make_hil_sensor(const sensors::SensorFrame& frame, uint64_t time_usec) {
  namespace bits = mavlink::hil_sensor;
  mavlink::msg::HilSensor m;
  m.time_usec = time_usec;
  if (frame.imu) {
    m.xacc = static_cast<float>(frame.imu->accel_FRD_m_s2.x());
    m.yacc = static_cast<float>(frame.imu->accel_FRD_m_s2.y());
    m.zacc = static_cast<float>(frame.imu->accel_FRD_m_s2.z());
    m.xgyro = static_cast<float>(frame.imu->gyro_FRD_rad_s.x());
    m.ygyro = static_cast<float>(frame.imu->gyro_FRD_rad_s.y());
    m.zgyro = static_cast<float>(frame.imu->gyro_FRD_rad_s.z());
    m.temperature = static_cast<float>(frame.imu->temperature_degC);
    m.fields_updated |= bits::kAccel | bits::kGyro;
  }
  if (frame.mag) {
    m.xmag = static_cast<float>(frame.mag->mag_FRD_gauss.x());
    m.ymag = static_cast<float>(frame.mag->mag_FRD_gauss.y());
    m.zmag = static_cast<float>(frame.mag->mag_FRD_gauss.z());
    m.fields_updated |= bits::kMag;
  }
  if (frame.baro) {
    m.abs_pressure = mavlink::wire::Pa_to_hPa(frame.baro->pressure_Pa);
    m.pressure_alt = static_cast<float>(frame.baro->pressure_alt_m);
    m.temperature = static_cast<float>(frame.baro->temperature_degC);
    m.fields_updated |= bits::kBaro;
  }
  m.id = 0;
  return m;
}

mavlink::msg::HilGps make_hil_gps(const sensors::GpsSample& gps, uint64_t time_usec) {
  namespace w = mavlink::wire;
  mavlink::msg::HilGps m;
  m.time_usec = time_usec;
  m.fix_type = gps.fix_type;
  m.lat = w::deg_to_degE7(gps.lat_deg);
  m.lon = w::deg_to_degE7(gps.lon_deg);
  m.alt = w::m_to_mm(gps.alt_m);
  m.eph = w::m_to_cm_u16(gps.eph_m);
  m.epv = w::m_to_cm_u16(gps.epv_m);
  m.vel = w::m_s_to_cm_s_u16(gps.ground_speed_m_s);
  m.vn = w::m_s_to_cm_s(gps.v_NED_m_s.x());
  m.ve = w::m_s_to_cm_s(gps.v_NED_m_s.y());
  m.vd = w::m_s_to_cm_s(gps.v_NED_m_s.z());
  m.cog = gps.ground_speed_m_s >= kCogMinSpeed_m_s ? w::deg_to_cdeg(gps.course_over_ground_deg) : w::kCogUnknown;
  m.satellites_visible = gps.satellites;
  m.id = 0;
  m.yaw = 0;  // 0: no GPS heading
  return m;
}

mavlink::msg::Odometry make_odometry(const sensors::GroundTruth& truth, uint64_t time_usec) {
  mavlink::msg::Odometry m;
  m.time_usec = time_usec;
  m.frame_id = static_cast<uint8_t>(mavlink::MavFrame::LocalNed);
  m.child_frame_id = static_cast<uint8_t>(mavlink::MavFrame::BodyFrd);
  m.x = static_cast<float>(truth.p_NED_m.x());
  m.y = static_cast<float>(truth.p_NED_m.y());
  m.z = static_cast<float>(truth.p_NED_m.z());
  m.q = wxyz(truth.q_FRD_to_NED);
  m.vx = static_cast<float>(truth.v_FRD_m_s.x());
  m.vy = static_cast<float>(truth.v_FRD_m_s.y());
  m.vz = static_cast<float>(truth.v_FRD_m_s.z());
  m.rollspeed = static_cast<float>(truth.w_FRD_rad_s.x());
  m.pitchspeed = static_cast<float>(truth.w_FRD_rad_s.y());
  m.yawspeed = static_cast<float>(truth.w_FRD_rad_s.z());
  for (int i = 0; i < 3; ++i) {
    m.pose_covariance[kCovarianceDiagonal[i]] = kOdometryPositionVariance_m2;
    m.pose_covariance[kCovarianceDiagonal[i + 3]] = kOdometryAttitudeVariance_rad2;
    m.velocity_covariance[kCovarianceDiagonal[i]] = kOdometryVelocityVariance_m2_s2;
    m.velocity_covariance[kCovarianceDiagonal[i + 3]] = kOdometryAttitudeVariance_rad2;
  }
  m.reset_counter = 0;
  m.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Vio);
  m.quality = 100;
  return m;
}

mavlink::msg::HilStateQuaternion make_hil_state_quaternion(const sensors::GroundTruth& truth, uint64_t time_usec) {
  namespace w = mavlink::wire;
  mavlink::msg::HilStateQuaternion m;
  m.time_usec = time_usec;
  m.attitude_quaternion = wxyz(truth.q_FRD_to_NED);
  m.rollspeed = static_cast<float>(truth.w_FRD_rad_s.x());
  m.pitchspeed = static_cast<float>(truth.w_FRD_rad_s.y());
  m.yawspeed = static_cast<float>(truth.w_FRD_rad_s.z());
  m.lat = w::deg_to_degE7(truth.lat_deg);
  m.lon = w::deg_to_degE7(truth.lon_deg);
  m.alt = w::m_to_mm(truth.alt_m);
  m.vx = w::m_s_to_cm_s(truth.v_NED_m_s.x());
  m.vy = w::m_s_to_cm_s(truth.v_NED_m_s.y());
  m.vz = w::m_s_to_cm_s(truth.v_NED_m_s.z());
  m.ind_airspeed = w::m_s_to_cm_s_u16(truth.v_NED_m_s.norm());
  m.true_airspeed = m.ind_airspeed;
  // Specific force in FRD, in mG (HIL_STATE_QUATERNION's unit).
  m.xacc = static_cast<int16_t>(std::lround(truth.accel_FRD_m_s2.x() / kGravity_m_s2 * 1000.0));
  m.yacc = static_cast<int16_t>(std::lround(truth.accel_FRD_m_s2.y() / kGravity_m_s2 * 1000.0));
  m.zacc = static_cast<int16_t>(std::lround(truth.accel_FRD_m_s2.z() / kGravity_m_s2 * 1000.0));
  return m;
}

}  // namespace hitl::hil
