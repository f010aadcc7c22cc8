#include "target/vio-server/odometry_to_vio.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include "base/mavlink/enums.h"

namespace hitl::vio {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;
using Vec3 = std::array<double, 3>;

bool finite(std::initializer_list<float> values) {
  for (float v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

/// R_FRD_to_local from q = (w, x, y, z), unit length: v_local = R v_FRD.
Mat3 rotation_from_quaternion(double w, double x, double y, double z) {
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

/// v_FRD = R^T v_local.
Vec3 local_to_body(const Mat3& R_FRD_to_local, const Vec3& v_local) {
  Vec3 out{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) out[i] += R_FRD_to_local[k][i] * v_local[k];
  }
  return out;
}

bool is_local_frame(uint8_t frame) {
  return frame == static_cast<uint8_t>(mavlink::MavFrame::LocalNed) ||
         frame == static_cast<uint8_t>(mavlink::MavFrame::LocalFrd);
}

void copy_diagonal(const std::array<float, 21>& from, float (&to)[21]) {
  bool known = true;
  for (float v : from) known = known && std::isfinite(v);
  for (float& v : to) v = 0.0f;
  if (!known) {
    to[0] = NAN;  // "If unknown, assign NaN value to first element in the array."
    return;
  }
  for (std::size_t i : kCovarianceDiagonal) to[i] = from[i];
}

}  // namespace

Expected<VioData> vio_from_odometry(const mavlink::msg::Odometry& odometry, int64_t timestamp_ns) {
  const auto& m = odometry;
  if (!is_local_frame(m.frame_id)) {
    return Error{"ODOMETRY frame_id " + std::to_string(m.frame_id) +
                 " is not a local frame hitl_vio can carry (MAV_FRAME_LOCAL_NED 1 or MAV_FRAME_LOCAL_FRD 20)"};
  }
  const bool twist_in_body = m.child_frame_id == static_cast<uint8_t>(mavlink::MavFrame::BodyFrd);
  if (!twist_in_body && !is_local_frame(m.child_frame_id)) {
    return Error{"ODOMETRY child_frame_id " + std::to_string(m.child_frame_id) +
                 " is not MAV_FRAME_BODY_FRD 12, MAV_FRAME_LOCAL_NED 1 or MAV_FRAME_LOCAL_FRD 20"};
  }
  if (!finite({m.x, m.y, m.z})) return Error{"ODOMETRY position is not finite"};
  if (!finite({m.q[0], m.q[1], m.q[2], m.q[3]})) return Error{"ODOMETRY quaternion is not finite"};
  if (!finite({m.vx, m.vy, m.vz})) return Error{"ODOMETRY velocity is not finite"};
  if (!finite({m.rollspeed, m.pitchspeed, m.yawspeed})) return Error{"ODOMETRY angular speed is not finite"};
  const double norm = std::sqrt(double(m.q[0]) * m.q[0] + double(m.q[1]) * m.q[1] + double(m.q[2]) * m.q[2] +
                                double(m.q[3]) * m.q[3]);
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    return Error{"ODOMETRY quaternion has length " + std::to_string(norm) + ", not 1"};
  }

  VioData v;
  std::memset(&v, 0, sizeof v);
  v.magic_number = kVioMagicNumber;
  v.timestamp_ns = timestamp_ns;
  v.frame = kVioFrameBodyAligned;

  // Pose: the VIO frame is the ODOMETRY pose frame (NED), the IMU frame is body FRD.
  v.T_imu_wrt_vio[0] = m.x;
  v.T_imu_wrt_vio[1] = m.y;
  v.T_imu_wrt_vio[2] = m.z;
  const Mat3 R_FRD_to_NED = rotation_from_quaternion(m.q[0] / norm, m.q[1] / norm, m.q[2] / norm, m.q[3] / norm);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) v.R_imu_to_vio[i][j] = static_cast<float>(R_FRD_to_NED[i][j]);
  }

  // Twist in the body (FRD): vision-hub's HITL reader rotates the velocity into the local frame itself.
  Vec3 vel{m.vx, m.vy, m.vz};
  Vec3 rate{m.rollspeed, m.pitchspeed, m.yawspeed};
  if (!twist_in_body) {
    vel = local_to_body(R_FRD_to_NED, vel);
    rate = local_to_body(R_FRD_to_NED, rate);
  }
  for (int i = 0; i < 3; ++i) {
    v.vel_imu_wrt_vio[i] = static_cast<float>(vel[i]);
    v.imu_angular_vel[i] = static_cast<float>(rate[i]);
  }

  copy_diagonal(m.pose_covariance, v.pose_covariance);
  copy_diagonal(m.velocity_covariance, v.velocity_covariance);

  v.gravity_vector[2] = kStandardGravity_m_s2;  // down the NED z axis
  for (int i = 0; i < 3; ++i) v.R_cam_to_imu[i][i] = 1.0f;

  if (m.quality < 0) {
    v.quality = -1;
    v.state = kVioStateFailed;
    v.error_code = kErrorCodeUnknown;
  } else {
    v.quality = m.quality == 0 ? kUnknownQuality : std::min<int32_t>(m.quality, 100);
    v.state = kVioStateOk;
  }
  return v;
}

ExtVioData extended_vio(const VioData& vio, int32_t frame_id) {
  ExtVioData e;
  std::memset(&e, 0, sizeof e);
  e.v = vio;
  e.last_cam_frame_id = frame_id;
  e.last_cam_timestamp_ns = vio.timestamp_ns;
  return e;
}

}  // namespace hitl::vio
