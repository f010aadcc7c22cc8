// Frame conversions, each checked against a known rotation.
#include "engine/frames/frames.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hitl::frames {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Quaterniond about_z(double angle_rad) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ())); }
Eigen::Quaterniond about_y(double angle_rad) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitY())); }

void expect_same_rotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  EXPECT_NEAR(std::abs(a.normalized().dot(b.normalized())), 1.0, 1e-12) << a.coeffs().transpose() << " vs " << b.coeffs().transpose();
}

TEST(Frames, VectorAxisSwaps) {
  EXPECT_EQ(enu_to_ned({1.0, 2.0, 3.0}), Eigen::Vector3d(2.0, 1.0, -3.0));  // NED = (y, x, -z)
  EXPECT_EQ(ned_to_enu({2.0, 1.0, -3.0}), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(flu_to_frd({1.0, 2.0, 3.0}), Eigen::Vector3d(1.0, -2.0, -3.0));  // FRD = (x, -y, -z)
  EXPECT_EQ(frd_to_flu({1.0, -2.0, -3.0}), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(R_ENU_to_NED() * Eigen::Vector3d(1, 2, 3), enu_to_ned({1, 2, 3}));
  EXPECT_EQ(R_FLU_to_FRD() * Eigen::Vector3d(1, 2, 3), flu_to_frd({1, 2, 3}));
  EXPECT_NEAR(R_ENU_to_NED().determinant(), 1.0, 1e-15);
  EXPECT_NEAR(R_FLU_to_FRD().determinant(), 1.0, 1e-15);
}

TEST(Frames, NoseNorthLevelIsIdentityInNedFrd) {
  // Body x (nose) along ENU y (north): a 90 deg turn about ENU z.
  const Eigen::Quaterniond q = q_FRD_to_NED_from(about_z(kPi / 2));
  expect_same_rotation(q, Eigen::Quaterniond::Identity());
}

TEST(Frames, NoseEastIsYaw90) {
  // FLU aligned with ENU: the nose points east, heading +90 deg; ODOMETRY q = (cos 45, 0, 0, sin 45).
  const Eigen::Quaterniond q = q_FRD_to_NED_from(Eigen::Quaterniond::Identity());
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.x(), 0.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.0, 1e-12);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-12);
  const EulerAngles e = euler_from(q);
  EXPECT_NEAR(e.yaw_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(e.roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(e.pitch_rad, 0.0, 1e-12);
  EXPECT_NEAR(heading_rad(Eigen::Quaterniond::Identity()), kPi / 2, 1e-12);
}

TEST(Frames, YawEnuFromTheAttitudeAndFromAHeadingAgree) {
  // Nose east: ENU yaw 0, heading +90 deg; nose north: ENU yaw +90 deg, heading 0; nose west: +-180.
  EXPECT_NEAR(yaw_ENU_rad(Eigen::Quaterniond::Identity()), 0.0, 1e-12);
  EXPECT_NEAR(yaw_ENU_from_heading_rad(kPi / 2), 0.0, 1e-12);
  EXPECT_NEAR(yaw_ENU_from_heading_rad(0.0), kPi / 2, 1e-12);
  EXPECT_NEAR(std::fabs(yaw_ENU_from_heading_rad(-kPi / 2)), kPi, 1e-12);
  for (double yaw = -3.0; yaw <= 3.0; yaw += 0.5) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
    EXPECT_NEAR(yaw_ENU_rad(q), yaw, 1e-9);
    EXPECT_NEAR(yaw_ENU_from_heading_rad(heading_rad(q)), yaw, 1e-9);
    EXPECT_LE(std::fabs(yaw_ENU_from_heading_rad(heading_rad(q))), kPi);
  }
}

TEST(Frames, NoseUpIsPositivePitch) {
  // Facing north, nose raised 10 deg: in FLU that is a rotation about -y (left axis).
  const Eigen::Quaterniond q_FLU_to_ENU = about_z(kPi / 2) * about_y(-10.0 * kPi / 180);
  const EulerAngles e = euler_from(q_FRD_to_NED_from(q_FLU_to_ENU));
  EXPECT_NEAR(e.pitch_rad, 10.0 * kPi / 180, 1e-12);
  EXPECT_NEAR(e.roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(e.yaw_rad, 0.0, 1e-12);
  // And its angular velocity: -y FLU is +y FRD.
  EXPECT_EQ(flu_to_frd({0.0, -0.5, 0.0}), Eigen::Vector3d(0.0, 0.5, 0.0));
}

TEST(Frames, AttitudeMapsVectorsConsistently) {
  // For any attitude, rotating a body vector then converting equals converting then rotating.
  for (int i = 0; i < 20; ++i) {
    const Eigen::Quaterniond q_FLU_to_ENU = Eigen::Quaterniond::UnitRandom();
    const Eigen::Vector3d v_FLU = Eigen::Vector3d::Random();
    const Eigen::Vector3d via_engine = enu_to_ned(q_FLU_to_ENU * v_FLU);
    const Eigen::Vector3d via_wire = q_FRD_to_NED_from(q_FLU_to_ENU) * flu_to_frd(v_FLU);
    EXPECT_LT((via_engine - via_wire).norm(), 1e-12);
    expect_same_rotation(q_FLU_to_ENU_from(q_FRD_to_NED_from(q_FLU_to_ENU)), q_FLU_to_ENU);
    EXPECT_GE(q_FRD_to_NED_from(q_FLU_to_ENU).w(), 0.0);
  }
}

TEST(Frames, EulerRoundTrip) {
  const EulerAngles in{0.1, -0.2, 2.5};
  const EulerAngles out = euler_from(q_FRD_to_NED_from(in));
  EXPECT_NEAR(out.roll_rad, in.roll_rad, 1e-12);
  EXPECT_NEAR(out.pitch_rad, in.pitch_rad, 1e-12);
  EXPECT_NEAR(out.yaw_rad, in.yaw_rad, 1e-12);
}

}  // namespace
}  // namespace hitl::frames
