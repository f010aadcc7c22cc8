#include "engine/frames/frames.h"

#include <algorithm>
#include <cmath>

namespace hitl::frames {

Eigen::Vector3d enu_to_ned(const Eigen::Vector3d& v_ENU) { return {v_ENU.y(), v_ENU.x(), -v_ENU.z()}; }
Eigen::Vector3d ned_to_enu(const Eigen::Vector3d& v_NED) { return {v_NED.y(), v_NED.x(), -v_NED.z()}; }
Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v_FLU) { return {v_FLU.x(), -v_FLU.y(), -v_FLU.z()}; }
Eigen::Vector3d frd_to_flu(const Eigen::Vector3d& v_FRD) { return {v_FRD.x(), -v_FRD.y(), -v_FRD.z()}; }

const Eigen::Matrix3d& R_ENU_to_NED() {
  static const Eigen::Matrix3d R = (Eigen::Matrix3d() << 0, 1, 0,  //
                                    1, 0, 0,                        //
                                    0, 0, -1)
                                       .finished();
  return R;
}

const Eigen::Matrix3d& R_FLU_to_FRD() {
  static const Eigen::Matrix3d R = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return R;
}

Eigen::Quaterniond q_FRD_to_NED_from(const Eigen::Quaterniond& q_FLU_to_ENU) {
  // Both constant maps are involutions, so R_FRD_to_FLU = R_FLU_to_FRD and R_NED_to_ENU = R_ENU_to_NED.
  const Eigen::Matrix3d R_FRD_to_NED = R_ENU_to_NED() * q_FLU_to_ENU.normalized().toRotationMatrix() * R_FLU_to_FRD();
  Eigen::Quaterniond q(R_FRD_to_NED);
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two equal quaternions: w >= 0
  return q.normalized();
}

Eigen::Quaterniond q_FLU_to_ENU_from(const Eigen::Quaterniond& q_FRD_to_NED) {
  const Eigen::Matrix3d R_FLU_to_ENU = R_ENU_to_NED() * q_FRD_to_NED.normalized().toRotationMatrix() * R_FLU_to_FRD();
  Eigen::Quaterniond q(R_FLU_to_ENU);
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q.normalized();
}

EulerAngles euler_from(const Eigen::Quaterniond& q_FRD_to_NED) {
  const Eigen::Matrix3d R = q_FRD_to_NED.normalized().toRotationMatrix();  // R = Rz(yaw) Ry(pitch) Rx(roll)
  EulerAngles e;
  e.pitch_rad = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  e.roll_rad = std::atan2(R(2, 1), R(2, 2));
  e.yaw_rad = std::atan2(R(1, 0), R(0, 0));
  return e;
}

Eigen::Quaterniond q_FRD_to_NED_from(const EulerAngles& euler) {
  return Eigen::AngleAxisd(euler.yaw_rad, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(euler.pitch_rad, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(euler.roll_rad, Eigen::Vector3d::UnitX());
}

double heading_rad(const Eigen::Quaterniond& q_FLU_to_ENU) {
  return euler_from(q_FRD_to_NED_from(q_FLU_to_ENU)).yaw_rad;
}

double yaw_ENU_rad(const Eigen::Quaterniond& q_FLU_to_ENU) {
  const Eigen::Matrix3d R_FLU_to_ENU = q_FLU_to_ENU.toRotationMatrix();
  return std::atan2(R_FLU_to_ENU(1, 0), R_FLU_to_ENU(0, 0));  // FLU x expressed in ENU: (east, north)
}

double yaw_ENU_from_heading_rad(double heading_rad) { return std::remainder(M_PI / 2 - heading_rad, 2 * M_PI); }

}  // namespace hitl::frames
