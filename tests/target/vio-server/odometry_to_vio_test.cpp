// odometry_to_vio: what each ODOMETRY field becomes in ModalAI's vio_data_t / ext_vio_data_t,
// with closed-form expectations (rotations of 90 degrees, a pitched body moving forward).
#include "target/vio-server/odometry_to_vio.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "base/mavlink/enums.h"

namespace hitl::vio {
namespace {

using mavlink::MavFrame;

mavlink::msg::Odometry level_odometry() {
  mavlink::msg::Odometry m;
  m.frame_id = static_cast<uint8_t>(MavFrame::LocalNed);
  m.child_frame_id = static_cast<uint8_t>(MavFrame::BodyFrd);
  m.q = {1, 0, 0, 0};
  m.quality = 100;
  return m;
}

/// q (w, x, y, z) for a rotation of `angle_rad` about a unit axis.
std::array<float, 4> axis_angle(double x, double y, double z, double angle_rad) {
  const double s = std::sin(angle_rad / 2);
  return {float(std::cos(angle_rad / 2)), float(x * s), float(y * s), float(z * s)};
}

TEST(OdometryToVio, PoseVelocityRatesAndConstantsOfALevelVehicle) {
  auto m = level_odometry();
  m.x = 1.5f;
  m.y = -2.0f;
  m.z = -3.25f;
  m.vx = 0.5f;
  m.vy = -0.25f;
  m.vz = 0.125f;
  m.rollspeed = 0.01f;
  m.pitchspeed = -0.02f;
  m.yawspeed = 0.03f;
  auto v = vio_from_odometry(m, 123456789);
  ASSERT_TRUE(v.ok()) << v.error().message;
  EXPECT_EQ(v->magic_number, 0x05455524u);
  EXPECT_EQ(v->timestamp_ns, 123456789);
  EXPECT_EQ(v->T_imu_wrt_vio[0], 1.5f);
  EXPECT_EQ(v->T_imu_wrt_vio[1], -2.0f);
  EXPECT_EQ(v->T_imu_wrt_vio[2], -3.25f);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_FLOAT_EQ(v->R_imu_to_vio[i][j], i == j ? 1.0f : 0.0f);
  }
  EXPECT_EQ(v->vel_imu_wrt_vio[0], 0.5f);
  EXPECT_EQ(v->vel_imu_wrt_vio[1], -0.25f);
  EXPECT_EQ(v->vel_imu_wrt_vio[2], 0.125f);
  EXPECT_EQ(v->imu_angular_vel[0], 0.01f);
  EXPECT_EQ(v->imu_angular_vel[1], -0.02f);
  EXPECT_EQ(v->imu_angular_vel[2], 0.03f);
  EXPECT_EQ(v->gravity_vector[0], 0.0f);
  EXPECT_EQ(v->gravity_vector[1], 0.0f);
  EXPECT_FLOAT_EQ(v->gravity_vector[2], 9.80665f);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(v->T_cam_wrt_imu[i], 0.0f);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(v->R_cam_to_imu[i][j], i == j ? 1.0f : 0.0f);
  }
  EXPECT_EQ(v->quality, 100);
  EXPECT_EQ(v->state, kVioStateOk);
  EXPECT_EQ(v->error_code, 0u);
  EXPECT_EQ(v->n_feature_points, 0);
  EXPECT_EQ(v->frame, kVioFrameBodyAligned);
}

TEST(OdometryToVio, RotationMatrixTakesBodyVectorsIntoNed) {
  auto m = level_odometry();
  // Yaw 90 degrees right: the nose (body x) points east (NED y); body y (right wing) points south.
  m.q = axis_angle(0, 0, 1, M_PI / 2);
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  const float expected_yaw[3][3] = {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(v->R_imu_to_vio[i][j], expected_yaw[i][j], 1e-6) << i << "," << j;
  }
  // Nose up 90 degrees: body x points up (NED -z), body z (down) points north.
  m.q = axis_angle(0, 1, 0, M_PI / 2);
  v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  const float expected_pitch[3][3] = {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(v->R_imu_to_vio[i][j], expected_pitch[i][j], 1e-6) << i << "," << j;
  }
}

TEST(OdometryToVio, BodyVelocityStaysInTheBodyForVisionHub) {
  // voxl-vision-hub's HITL reader computes v_local = R_imu_to_vio * vel_imu_wrt_vio itself.
  auto m = level_odometry();
  m.q = axis_angle(0, 0, 1, M_PI / 2);  // facing east
  m.vx = 2.0f;                          // forward
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->vel_imu_wrt_vio[0], 2.0f);
  EXPECT_EQ(v->vel_imu_wrt_vio[1], 0.0f);
  double east = 0;
  for (int j = 0; j < 3; ++j) east += v->R_imu_to_vio[1][j] * v->vel_imu_wrt_vio[j];
  EXPECT_NEAR(east, 2.0, 1e-6);  // what vision-hub then sees: moving east at 2 m/s
}

TEST(OdometryToVio, TwistInTheLocalFrameIsRotatedIntoTheBody) {
  auto m = level_odometry();
  m.child_frame_id = static_cast<uint8_t>(MavFrame::LocalNed);
  m.q = axis_angle(0, 0, 1, M_PI / 2);  // facing east
  m.vy = 3.0f;                          // moving east: forward in the body
  m.yawspeed = 0.5f;                    // yaw rate about NED z = body z when level
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  EXPECT_NEAR(v->vel_imu_wrt_vio[0], 3.0f, 1e-6);
  EXPECT_NEAR(v->vel_imu_wrt_vio[1], 0.0f, 1e-6);
  EXPECT_NEAR(v->imu_angular_vel[2], 0.5f, 1e-6);
  m.frame_id = static_cast<uint8_t>(MavFrame::LocalFrd);
  EXPECT_TRUE(vio_from_odometry(m, 0).ok());
}

TEST(OdometryToVio, CovarianceDiagonalsAreCopiedAndTheRestIsZero) {
  auto m = level_odometry();
  for (std::size_t i = 0; i < 21; ++i) {
    m.pose_covariance[i] = 100.0f + float(i);
    m.velocity_covariance[i] = 200.0f + float(i);
  }
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  for (std::size_t i = 0; i < 21; ++i) {
    const bool diagonal = i == 0 || i == 6 || i == 11 || i == 15 || i == 18 || i == 20;
    EXPECT_EQ(v->pose_covariance[i], diagonal ? 100.0f + float(i) : 0.0f) << i;
    EXPECT_EQ(v->velocity_covariance[i], diagonal ? 200.0f + float(i) : 0.0f) << i;
  }
  m.pose_covariance[0] = NAN;  // MAVLink's "unknown"
  v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(std::isnan(v->pose_covariance[0]));
  EXPECT_EQ(v->pose_covariance[6], 0.0f);
  EXPECT_EQ(v->velocity_covariance[6], 206.0f);
}

TEST(OdometryToVio, QualityAndState) {
  auto m = level_odometry();
  const std::pair<int8_t, int32_t> cases[] = {{100, 100}, {1, 1}, {73, 73}, {0, kUnknownQuality}, {120, 100}};
  for (auto [in, out] : cases) {
    m.quality = in;
    auto v = vio_from_odometry(m, 0);
    ASSERT_TRUE(v.ok());
    EXPECT_EQ(v->quality, out) << int(in);
    EXPECT_EQ(v->state, kVioStateOk);
    EXPECT_EQ(v->error_code, 0u);
  }
  m.quality = -1;
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->quality, -1);
  EXPECT_EQ(v->state, kVioStateFailed);
  EXPECT_EQ(v->error_code, kErrorCodeUnknown);
}

TEST(OdometryToVio, SlightlyDenormalisedQuaternionIsNormalised) {
  auto m = level_odometry();
  m.q = {1.0005f, 0, 0, 0};
  auto v = vio_from_odometry(m, 0);
  ASSERT_TRUE(v.ok());
  EXPECT_NEAR(v->R_imu_to_vio[0][0], 1.0f, 1e-6);
}

TEST(OdometryToVio, RefusesWhatCannotBeAPose) {
  auto bad = [](auto edit) {
    auto m = level_odometry();
    edit(m);
    auto v = vio_from_odometry(m, 0);
    return v.ok() ? std::string("accepted") : v.error().message;
  };
  EXPECT_NE(bad([](auto& m) { m.x = NAN; }).find("position"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.q[2] = INFINITY; }).find("quaternion"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.q = {0, 0, 0, 0}; }).find("length"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.q = {2, 0, 0, 0}; }).find("length"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.vz = NAN; }).find("velocity"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.pitchspeed = NAN; }).find("angular"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.frame_id = 12; }).find("frame_id 12"), std::string::npos);
  EXPECT_NE(bad([](auto& m) { m.child_frame_id = 21; }).find("child_frame_id 21"), std::string::npos);
}

TEST(OdometryToVio, ExtendedRecordCarriesTheSamePose) {
  auto m = level_odometry();
  m.x = 4.0f;
  auto v = vio_from_odometry(m, 987654321);
  ASSERT_TRUE(v.ok());
  const ExtVioData e = extended_vio(v.value(), 42);
  EXPECT_EQ(std::memcmp(&e.v, &v.value(), sizeof(VioData)), 0);
  EXPECT_EQ(e.last_cam_frame_id, 42);
  EXPECT_EQ(e.last_cam_timestamp_ns, 987654321);
  EXPECT_EQ(e.imu_cam_time_shift_s, 0.0f);
  EXPECT_EQ(e.n_total_features, 0u);
  EXPECT_EQ(e.gyro_bias[0], 0.0f);
  EXPECT_EQ(e.features[63].id, 0u);
}

TEST(VioData, RecordBytesSitWhereModalAiReadsThem) {
  // Independent of the struct: a record written through it, read back by byte offset.
  VioData v;
  std::memset(&v, 0, sizeof v);
  v.magic_number = kVioMagicNumber;
  v.quality = -7;
  v.timestamp_ns = 0x0102030405060708;
  v.R_imu_to_vio[2][2] = 9.0f;
  v.velocity_covariance[20] = 4.0f;
  v.error_code = 0xA5A5A5A5;
  v.n_feature_points = 0x1234;
  v.state = kVioStateOk;
  v.frame = kVioFrameBodyAligned;
  uint8_t bytes[sizeof v];
  std::memcpy(bytes, &v, sizeof v);
  auto at = [&](std::size_t off, auto value) {
    decltype(value) out;
    std::memcpy(&out, bytes + off, sizeof out);
    return out;
  };
  EXPECT_EQ(sizeof bytes, 324u);
  EXPECT_EQ(bytes[0], 0x24);  // little-endian 0x05455524
  EXPECT_EQ(bytes[3], 0x05);
  EXPECT_EQ(at(4, int32_t{}), -7);
  EXPECT_EQ(at(8, int64_t{}), 0x0102030405060708);
  EXPECT_EQ(at(28 + 8 * 4, float{}), 9.0f);
  EXPECT_EQ(at(160 + 20 * 4, float{}), 4.0f);
  EXPECT_EQ(at(316, uint32_t{}), 0xA5A5A5A5u);
  EXPECT_EQ(at(320, uint16_t{}), 0x1234);
  EXPECT_EQ(bytes[322], 2);
  EXPECT_EQ(bytes[323], 2);
  EXPECT_EQ(sizeof(ExtVioData), 5268u);
}

}  // namespace
}  // namespace hitl::vio
