#include "engine/model/ground_contact.h"

#include <algorithm>

namespace hitl::model {
namespace {

double normal_force_N(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m, const Eigen::Vector3d& v_ENU_m_s) {
  const double depth_m = -p_ENU_m.z();
  if (depth_m <= 0.0) return 0.0;
  return std::max(0.0, gear.stiffness_N_m * depth_m - gear.damping_N_s_m * v_ENU_m_s.z());
}

}  // namespace

Eigen::Vector3d ground_contact_force_ENU_N(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                                           const Eigen::Vector3d& v_ENU_m_s, const ContactAnchor& anchor) {
  const double fn_N = normal_force_N(gear, p_ENU_m, v_ENU_m_s);
  if (fn_N <= 0.0) return Eigen::Vector3d::Zero();
  Eigen::Vector2d ft_N = -gear.tangential_damping_N_s_m * v_ENU_m_s.head<2>();
  if (anchor.set) ft_N -= gear.tangential_stiffness_N_m * (p_ENU_m.head<2>() - anchor.p_EN_m);
  const double cap_N = gear.friction_coefficient * fn_N;
  const double ft_norm_N = ft_N.norm();
  if (ft_norm_N > cap_N) ft_N *= cap_N / ft_norm_N;
  return {ft_N.x(), ft_N.y(), fn_N};
}

void update_contact_anchor(const LandingGearConfig& gear, const Eigen::Vector3d& p_ENU_m,
                           const Eigen::Vector3d& v_ENU_m_s, ContactAnchor& anchor) {
  const double fn_N = normal_force_N(gear, p_ENU_m, v_ENU_m_s);
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

}  // namespace hitl::model
