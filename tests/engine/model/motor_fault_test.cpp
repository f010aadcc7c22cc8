// A motor fault (engine/faults' motor:i,k) in the model: the thrust and torques of motor i x k, and
// the roll, pitch and yaw accelerations the x500's geometry implies when it is lost in a hover.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/frames/frames.h"
#include "engine/model/motor_model.h"
#include "engine/model/multicopter.h"
#include "engine/model/x500_defaults.h"

namespace hitl::model {
namespace {

TEST(MotorFault, ScalesThrustAndTorqueOfTheRotor) {
  const RotorConfig r = x500_vehicle_config().rotors[0];
  const RotorLoads full = rotor_loads(r, 700.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 0, 0));
  const RotorLoads weak = scaled_rotor_loads(full, 0.6);
  EXPECT_TRUE(weak.force_at_hub_ENU_N.isApprox(0.6 * full.force_at_hub_ENU_N));
  EXPECT_TRUE(weak.torque_on_frame_ENU_Nm.isApprox(0.6 * full.torque_on_frame_ENU_Nm));
  EXPECT_TRUE(scaled_rotor_loads(full, 0.0).force_at_hub_ENU_N.isZero());
}

TEST(MotorFault, FrontRightOutInAHoverRollsRightPitchesDownYawsLeft) {
  const VehicleConfig v = x500_vehicle_config();
  const WorldConfig w = default_world_config();
  auto created = Multicopter::create(v, w, 1);
  ASSERT_TRUE(created) << created.error().message;
  Multicopter& m = **created;
  const double u_h = hover_command(v, w);
  InitialCondition ic;
  ic.p_ENU_m = {0, 0, 5};
  ic.rotor_speed_rad_s.fill(u_h * v.rotors[0].input_scaling_rad_s);
  m.reset(ic);
  m.set_motor_commands({{u_h, u_h, u_h, u_h}, true});
  m.set_motor_effectiveness(0, 0.0);  // motor 0: front-right, CCW
  ASSERT_TRUE(m.step());

  // Closed form: the healthy three lose motor 0's moment about the centre. Its thrust T = m g / 4 at
  // r0 = (x, -y) FLU gave r0 x T z = (-y T... ) = (r0.y T, -r0.x T, 0); its drag torque -kM T z (CCW).
  double mass_kg = v.base.mass_kg;
  for (const auto& r : v.rotors) mass_kg += r.mass_kg;
  const double thrust_N = mass_kg * w.gravity_m_s2 / 4.0;
  const Eigen::Vector3d r0 = v.rotors[0].position_FLU_m;
  const Eigen::Vector3d lost_torque_FLU_Nm(r0.y() * thrust_N, -r0.x() * thrust_N, -v.rotors[0].moment_constant_m * thrust_N);
  const Eigen::Vector3d torque_FLU_Nm = -lost_torque_FLU_Nm;  // what is left: the others' unbalanced moment
  // Inertia about the base origin: the base plus the rotors as point masses at their hubs and their own inertia.
  Eigen::Vector3d inertia_kgm2 = v.base.inertia_kgm2;
  for (const auto& r : v.rotors) {
    const Eigen::Vector3d p = r.position_FLU_m;
    inertia_kgm2 += r.inertia_kgm2 + r.mass_kg * Eigen::Vector3d(p.y() * p.y() + p.z() * p.z(), p.x() * p.x() + p.z() * p.z(),
                                                                  p.x() * p.x() + p.y() * p.y());
  }
  const Eigen::Vector3d expected_FLU_rad_s2 = torque_FLU_Nm.cwiseQuotient(inertia_kgm2);
  const Eigen::Vector3d alpha_FLU_rad_s2 = m.state().alpha_FLU_rad_s2;
  EXPECT_NEAR(alpha_FLU_rad_s2.x(), expected_FLU_rad_s2.x(), 0.1 * std::abs(expected_FLU_rad_s2.x()));
  EXPECT_NEAR(alpha_FLU_rad_s2.y(), expected_FLU_rad_s2.y(), 0.1 * std::abs(expected_FLU_rad_s2.y()));
  EXPECT_NEAR(alpha_FLU_rad_s2.z(), expected_FLU_rad_s2.z(), 0.15 * std::abs(expected_FLU_rad_s2.z()));
  // In the wire's FRD: right side down (+roll), nose down (-pitch), heading decreasing (-yaw).
  const Eigen::Vector3d alpha_FRD = frames::flu_to_frd(alpha_FLU_rad_s2);
  EXPECT_GT(alpha_FRD.x(), 0);
  EXPECT_LT(alpha_FRD.y(), 0);
  EXPECT_LT(alpha_FRD.z(), 0);
  // And a quarter of the lift is gone: the vertical acceleration is about -g/4.
  EXPECT_NEAR(m.state().a_ENU_m_s2.z(), -w.gravity_m_s2 / 4.0, 0.3);
}

TEST(MotorFault, HealthyAgainWhenSetBackToOne) {
  auto created = Multicopter::create(x500_vehicle_config(), default_world_config(), 1);
  ASSERT_TRUE(created);
  Multicopter& m = **created;
  const double u_h = hover_command(m.vehicle_config(), m.world_config());
  InitialCondition ic;
  ic.p_ENU_m = {0, 0, 5};
  ic.rotor_speed_rad_s.fill(u_h * m.vehicle_config().rotors[0].input_scaling_rad_s);
  m.reset(ic);
  m.set_motor_commands({{u_h, u_h, u_h, u_h}, true});
  m.set_motor_effectiveness(1, 0.5);
  m.set_motor_effectiveness(1, 1.0);
  ASSERT_TRUE(m.step());
  EXPECT_LT(m.state().alpha_FLU_rad_s2.norm(), 0.05);
}

}  // namespace
}  // namespace hitl::model
