// The vehicle's state after a physics step, as plain values in the engine's frames (world ENU,
// body FLU). Sensors and ground truth are computed from this; engine/frames converts to NED/FRD.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hitl::model {

struct VehicleState {
  double time_s = 0.0;        ///< simulated time since reset
  std::uint64_t step = 0;     ///< outer steps since reset
  Eigen::Vector3d p_ENU_m = Eigen::Vector3d::Zero();      ///< base origin; ENU origin = ground at home
  Eigen::Quaterniond q_FLU_to_ENU = Eigen::Quaterniond::Identity();  ///< attitude
  Eigen::Vector3d v_ENU_m_s = Eigen::Vector3d::Zero();    ///< base origin velocity
  Eigen::Vector3d a_ENU_m_s2 = Eigen::Vector3d::Zero();   ///< base origin acceleration over the last step
  Eigen::Vector3d w_FLU_rad_s = Eigen::Vector3d::Zero();  ///< body angular velocity, expressed in FLU
  Eigen::Vector3d alpha_FLU_rad_s2 = Eigen::Vector3d::Zero();  ///< body angular acceleration over the last step
  /// Specific force at the base origin (a - g), in FLU, averaged over the step (the mean over the
  /// physics sub-steps, each in its own body frame): what an accelerometer there reads, as its
  /// output filter averages the samples between two readings.
  Eigen::Vector3d specific_force_FLU_m_s2 = Eigen::Vector3d::Zero();
  /// Body angular velocity averaged over the step (the sub-steps' mean): what a gyro reads.
  Eigen::Vector3d w_step_mean_FLU_rad_s = Eigen::Vector3d::Zero();
  std::array<double, 4> rotor_speed_rad_s{};  ///< spin rate magnitude per rotor, PX4 motor order
  Eigen::Vector3d wind_ENU_m_s = Eigen::Vector3d::Zero();  ///< air velocity (mean + gust) this step
  bool on_ground = false;  ///< any contact point (legs or frame) touches the ground
  /// Height of the lowest contact point above the ground (negative: compressed into it).
  double ground_clearance_m = 0.0;
};

}  // namespace hitl::model
