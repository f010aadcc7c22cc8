#include "engine/model/ground_contact.h"

#include <algorithm>

namespace hitl::model {
namespace {

double normal_force_N(const ContactPoint& point, const Eigen::Vector3d& p_ENU_m, const Eigen::Vector3d& v_ENU_m_s) {
  const double depth_m = -p_ENU_m.z();
  if (depth_m <= 0.0) return 0.0;
  const double ramp = point.damping_depth_m > 0.0 ? std::min(1.0, depth_m / point.damping_depth_m) : 1.0;
  return std::max(0.0, point.stiffness_N_m * depth_m - ramp * point.damping_N_s_m * v_ENU_m_s.z());
}

ContactPoint leg(const LandingGearConfig& gear, const Eigen::Vector3d& p_FLU_m) {
  return {p_FLU_m, gear.stiffness_N_m, gear.damping_N_s_m, gear.damping_depth_m};
}

}  // namespace

std::array<ContactPoint, kContactPoints> contact_points(const LandingGearConfig& gear) {
  std::array<ContactPoint, kContactPoints> out;
  for (std::size_t k = 0; k < 4; ++k) {
    out[k] = leg(gear, gear.contact_points_FLU_m[k]);
    out[4 + k] = {gear.frame_points_FLU_m[k], gear.frame_stiffness_N_m, gear.frame_damping_N_s_m, 0.0};
  }
  return out;
}

Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const ContactPoint& point,
                                           const Eigen::Vector3d& p_ENU_m, const Eigen::Vector3d& v_ENU_m_s,
                                           const ContactAnchor& anchor) {
  const double fn_N = normal_force_N(point, p_ENU_m, v_ENU_m_s);
  if (fn_N <= 0.0) return Eigen::Vector3d::Zero();
  Eigen::Vector2d ft_N = -gear.tangential_damping_N_s_m * v_ENU_m_s.head<2>();
  if (anchor.set) ft_N -= gear.tangential_stiffness_N_m * (p_ENU_m.head<2>() - anchor.p_EN_m);
  const double cap_N = gear.friction_coefficient * fn_N;
  const double ft_norm_N = ft_N.norm();
  if (ft_norm_N > cap_N) ft_N *= cap_N / ft_norm_N;
  return {ft_N.x(), ft_N.y(), fn_N};
}

Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                                           const Eigen::Vector3d& v_ENU_m_s, const ContactAnchor& anchor) {
  return ground_contact_force_ENU_N(gear, leg(gear, Eigen::Vector3d::Zero()), p_ENU_m, v_ENU_m_s, anchor);
}

void update_contact_anchor(const LandingGearConfig& gear, const ContactPoint& point, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor) {
  const double fn_N = normal_force_N(point, p_ENU_m, v_ENU_m_s);
  if (p_ENU_m.z() >= 0.0) {
    anchor.set = false;
    return;
  }
  if (!anchor.set) {
    anchor = {p_ENU_m.head<2>(), true};
    return;
  }
  const Eigen::Vector2d spring_N = -gear.tangential_stiffness_N_m * (p_ENU_m.head<2>() - anchor.p_EN_m);
  const double cap_N = gear.friction_coefficient * fn_N;
  const double spring_norm_N = spring_N.norm();
  if (spring_norm_N > cap_N) {
    // Slipping: put the anchor where the spring pulls with exactly mu Fn, behind the point.
    anchor.p_EN_m = p_ENU_m.head<2>() + spring_N / spring_norm_N * (cap_N / gear.tangential_stiffness_N_m);
  }
}

void update_contact_anchor(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor) {
  update_contact_anchor(gear, leg(gear, Eigen::Vector3d::Zero()), p_ENU_m, v_ENU_m_s, anchor);
}

}  // namespace hitl::model
