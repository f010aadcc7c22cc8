// Landing gear and frame on flat ground (world ENU, ground at z = 0): per contact point a normal
// spring-damper that only pushes, Fn = max(0, k d - c(d) v_z) with penetration d = -z, and
// stick-slip friction: a tangential spring-damper to an anchor on the ground, capped at mu Fn.
// Between steps the anchor follows a point that slips (so the spring holds exactly mu Fn) or
// leaves the ground. (simbody-facts.md: this held a side load at rest and landed without drift;
// regularised Coulomb friction crept.)
//
// The legs (skid ends) are soft and damped as a real x500's legs and skids: a touchdown is stopped
// over tens of milliseconds, c(d) grows with the compression over `damping_depth_m` (no force step
// at first contact), and the damping is high enough that nothing is thrown back up. The frame
// points (motor tops) are stiff: a vehicle on its back or side rests on them without sinking.
#pragma once

#include <array>

#include <Eigen/Core>

#include "engine/model/vehicle_config.h"

namespace hitl::model {

struct ContactAnchor {
  Eigen::Vector2d p_EN_m = Eigen::Vector2d::Zero();  ///< stick point on the ground (east, north)
  bool set = false;
};

/// One point of the vehicle that can touch the ground, and its normal spring-damper.
struct ContactPoint {
  Eigen::Vector3d p_FLU_m = Eigen::Vector3d::Zero();
  double stiffness_N_m = 0.0;
  double damping_N_s_m = 0.0;
  double damping_depth_m = 0.0;  ///< full damping from this compression on (0: at once)
};

inline constexpr std::size_t kContactPoints = 8;  ///< 4 legs (skid ends), then 4 frame points

/// The legs' four points, then the frame's four.
std::array<ContactPoint, kContactPoints> contact_points(const LandingGearConfig& gear);

/// Force of the ground on a contact point at p moving at v (world ENU).
Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const ContactPoint& point,
                                           const Eigen::Vector3d& p_ENU_m, const Eigen::Vector3d& v_ENU_m_s,
                                           const ContactAnchor& anchor);
/// The same for a leg (skid end).
Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                                           const Eigen::Vector3d& v_ENU_m_s, const ContactAnchor& anchor);

/// Moves the anchor after a step: set on touch-down, dragged along while slipping, cleared on lift-off.
void update_contact_anchor(const LandingGearConfig& gear, const ContactPoint& point, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor);
void update_contact_anchor(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor);

}  // namespace hitl::model
