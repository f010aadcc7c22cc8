// Landing gear on flat ground (world ENU, ground at z = 0): per contact point a normal
// spring-damper that only pushes, Fn = max(0, k d - c v_z) with penetration d = -z, and stick-slip
// friction: a tangential spring-damper to an anchor on the ground, capped at mu Fn. Between steps
// the anchor follows a point that slips (so the spring holds exactly mu Fn) or leaves the ground.
// (simbody-facts.md: this held a side load at rest and landed without drift; regularised Coulomb
// friction crept.)
#pragma once

#include <Eigen/Core>

#include "engine/model/vehicle_config.h"

namespace hitl::model {

struct ContactAnchor {
  Eigen::Vector2d p_EN_m = Eigen::Vector2d::Zero();  ///< stick point on the ground (east, north)
  bool set = false;
};

/// Force of the ground on a contact point at p moving at v (world ENU).
Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                                           const Eigen::Vector3d& v_ENU_m_s, const ContactAnchor& anchor);

/// Moves the anchor after a step: set on touch-down, dragged along while slipping, cleared on lift-off.
void update_contact_anchor(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor);

}  // namespace hitl::model
