// Controller pieces with closed-form expectations: thrust -> attitude, attitude error -> rate
// direction, stick deadzone, position-control hover thrust, land detector stages.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "emulator/flight/attitude_control.h"
#include "emulator/flight/land_detector.h"
#include "emulator/flight/manual_setpoint.h"
#include "emulator/flight/position_control.h"

namespace hitl::flight {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PositionControl, LevelThrustGivesTheHeadingOnly) {
  const Eigen::Quaterniond q = attitude_from_thrust({0.0, 0.0, -0.6}, kPi / 2);
  const Eigen::Vector3d nose_NED = q * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(nose_NED.y(), 1.0, 1e-9);  // facing east
  EXPECT_NEAR((q * Eigen::Vector3d::UnitZ()).z(), 1.0, 1e-9);
}

TEST(PositionControl, AtTheSetpointItAsksForHoverThrust) {
  PositionControl pc;
  FlightParams p;
  PositionSetpoint sp;
  sp.p_NED_m = {1.0, 2.0, -3.0};
  VehicleKinematics k{{1.0, 2.0, -3.0}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const PositionControlOutput out = pc.update(sp, k, p, 0.004);
  EXPECT_NEAR(out.collective_thrust, p.MPC_THR_HOVER, 1e-6);
  EXPECT_NEAR(out.thrust_NED.z(), -p.MPC_THR_HOVER, 1e-6);
}

TEST(PositionControl, NorthErrorTiltsNoseDownWhenFacingNorth) {
  PositionControl pc;
  FlightParams p;
  PositionSetpoint sp;
  sp.p_NED_m = {5.0, 0.0, -3.0};
  VehicleKinematics k{{0.0, 0.0, -3.0}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const PositionControlOutput out = pc.update(sp, k, p, 0.004);
  EXPECT_GT(out.thrust_NED.x(), 0.0);  // thrust points up and north
  const Eigen::Vector3d nose_NED = out.q_sp_FRD_to_NED * Eigen::Vector3d::UnitX();
  EXPECT_GT(nose_NED.z(), 0.0);  // nose below the horizon
  EXPECT_LE(std::acos((out.q_sp_FRD_to_NED * Eigen::Vector3d::UnitZ()).z()), p.MPC_TILTMAX_AIR * kPi / 180 + 1e-9);
}

TEST(AttitudeControl, ErrorsTurnIntoRatesOfTheRightSign) {
  FlightParams p;
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond rolled_right(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond nose_up(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond yawed_right(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(attitude_control(level, rolled_right, 0.0, p).x(), 0.1 * p.MC_ROLL_P, 0.01);
  EXPECT_NEAR(attitude_control(level, nose_up, 0.0, p).y(), 0.1 * p.MC_PITCH_P, 0.01);
  EXPECT_NEAR(attitude_control(level, yawed_right, 0.0, p).z(), 0.1 * p.MC_YAW_P, 0.02);
  EXPECT_NEAR(attitude_control(level, level, 0.5, p).z(), 0.5, 1e-9);
}

TEST(ManualSetpoint, DeadzoneRescales) {
  EXPECT_DOUBLE_EQ(apply_deadzone(0.05, 0.1), 0.0);
  EXPECT_NEAR(apply_deadzone(0.55, 0.1), 0.5, 1e-12);
  EXPECT_NEAR(apply_deadzone(-1.0, 0.1), -1.0, 1e-12);
}

TEST(ManualSetpoint, PitchForwardFliesAlongTheHeading) {
  FlightParams p;
  ManualPositionSetpoint m;
  m.reset(Eigen::Vector3d::Zero(), kPi / 2);  // facing east
  StickInput s;
  s.pitch = 1.0;
  PositionSetpoint sp;
  for (int i = 0; i < 2000; ++i) sp = m.update(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), kPi / 2, p, 0.004);
  EXPECT_NEAR(sp.v_NED_m_s.y(), p.MPC_VEL_MANUAL, 1e-6);
  EXPECT_NEAR(sp.v_NED_m_s.x(), 0.0, 1e-6);
  EXPECT_TRUE(std::isnan(sp.p_NED_m.x()));
  EXPECT_NEAR(sp.p_NED_m.z(), 0.0, 1e-12);  // throttle centred: altitude held
}

TEST(LandDetector, ContactThenLowThrustThenLanded) {
  FlightParams p;
  LandDetector d;
  LandDetectorInput in;
  in.v_sp_NED_m_s.z() = p.MPC_LAND_SPEED;
  in.collective_thrust = 0.5;
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(d.update(in, p, 0.004));
  EXPECT_TRUE(d.ground_contact());
  in.collective_thrust = p.MPC_THR_MIN;
  bool landed = false;
  double t = 0.0;
  while (!landed && t < 5.0) {
    landed = d.update(in, p, 0.004);
    t += 0.004;
  }
  EXPECT_TRUE(landed);
  EXPECT_NEAR(t, p.LNDMC_TRIG_TIME, 0.01);
  in.v_NED_m_s.z() = 0.7;  // still descending: no contact
  d.reset();
  for (int i = 0; i < 500; ++i) EXPECT_FALSE(d.update(in, p, 0.004));
}

}  // namespace
}  // namespace hitl::flight
