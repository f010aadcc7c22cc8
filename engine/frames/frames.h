// The one place for frame conversions between the engine (world ENU, body FLU) and the MAVLink
// boundary (world NED, body FRD).
//
//   NED = (y_enu, x_enu, -z_enu)      FRD = (x_flu, -y_flu, -z_flu)
//
// Both maps are their own inverse. A rotation "R_A_to_B" maps a vector expressed in A to the same
// vector expressed in B (v_B = R_A_to_B * v_A); a quaternion "q_A_to_B" is the same rotation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hitl::frames {

/// Vector in world ENU -> the same vector in world NED.
Eigen::Vector3d enu_to_ned(const Eigen::Vector3d& v_ENU);
/// Vector in world NED -> the same vector in world ENU.
Eigen::Vector3d ned_to_enu(const Eigen::Vector3d& v_NED);
/// Vector in body FLU -> the same vector in body FRD.
Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v_FLU);
/// Vector in body FRD -> the same vector in body FLU.
Eigen::Vector3d frd_to_flu(const Eigen::Vector3d& v_FRD);

/// Constant rotations between the conventions (proper rotations, det = +1).
const Eigen::Matrix3d& R_ENU_to_NED();
const Eigen::Matrix3d& R_FLU_to_FRD();

/// Attitude: body FLU in world ENU -> body FRD in world NED.
/// R_FRD_to_NED = R_ENU_to_NED * R_FLU_to_ENU * R_FRD_to_FLU.
Eigen::Quaterniond q_FRD_to_NED_from(const Eigen::Quaterniond& q_FLU_to_ENU);
/// The inverse of q_FRD_to_NED_from.
Eigen::Quaterniond q_FLU_to_ENU_from(const Eigen::Quaterniond& q_FRD_to_NED);

/// Aerospace Euler angles (roll about x, pitch about y, yaw about z; z-y-x order) of an FRD->NED
/// attitude, in radians. Yaw is the heading: 0 north, +pi/2 east.
struct EulerAngles {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
};
EulerAngles euler_from(const Eigen::Quaterniond& q_FRD_to_NED);
Eigen::Quaterniond q_FRD_to_NED_from(const EulerAngles& euler);

/// Heading (yaw, radians, 0 north, +pi/2 east) of a vehicle whose body FLU has attitude q_FLU_to_ENU.
double heading_rad(const Eigen::Quaterniond& q_FLU_to_ENU);
/// Yaw in world ENU (radians, 0 east, counter-clockwise positive, in [-pi, pi]) of a vehicle whose
/// body FLU has attitude q_FLU_to_ENU: the direction of its nose (FLU x) in the ENU x-y plane.
double yaw_ENU_rad(const Eigen::Quaterniond& q_FLU_to_ENU);
/// The same yaw from a NED heading (0 north, +pi/2 east): yaw_ENU = pi/2 - heading, in [-pi, pi].
double yaw_ENU_from_heading_rad(double heading_rad);

}  // namespace hitl::frames
