// ModalAI's VIO pipe records, vio_data_t (324 bytes) and ext_vio_data_t (5268 bytes), as
// libmodal_pipe defines them: library/include/modal_pipe_interfaces.h (2022) and, since the 2025
// split, include/pipe_interfaces/vio_data_t.h of gitlab.com/voxl-public/voxl-sdk/core-libs/libmodal-pipe.
// These are our own definitions of that wire layout (packed, little-endian); the static_asserts
// below pin the size and every offset, so a change of layout cannot slip through. Field names are
// ModalAI's, so that code reads like the header it mirrors.
//
// Frames, in ModalAI's words: T_A_wrt_B is the position of frame A's origin in frame B,
// R_A_to_B rotates a vector from frame A into frame B. What hitl puts in each field, and in which
// frame, is decided in one place: odometry_to_vio.h.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

namespace hitl::vio {

static_assert(std::endian::native == std::endian::little, "MPA records are little-endian");

/// VIO_MAGIC_NUMBER: the first field of every record, for re-synchronising a reader.
inline constexpr uint32_t kVioMagicNumber = 0x05455524;

/// vio_data_t.state: VIO_STATE_FAILED / VIO_STATE_INITIALIZING / VIO_STATE_OK.
inline constexpr uint8_t kVioStateFailed = 0;
inline constexpr uint8_t kVioStateInitializing = 1;
inline constexpr uint8_t kVioStateOk = 2;

/// vio_data_t.frame (the byte was `reserved` before libmodal_pipe's 2024 change):
/// VIO_FRAME_UNKNOWN / VIO_FRAME_IMU_UNALIGNED / VIO_FRAME_BODY_ALIGNED. BODY_ALIGNED: the
/// VIO frame is gravity aligned with z down (FRD-style axes), the pose is the IMU's.
inline constexpr uint8_t kVioFrameUnknown = 0;
inline constexpr uint8_t kVioFrameImuUnaligned = 1;
inline constexpr uint8_t kVioFrameBodyAligned = 2;

/// vio_data_t.error_code bit ERROR_CODE_UNKNOWN (1 << 20): set when the source reports failure.
inline constexpr uint32_t kErrorCodeUnknown = 1u << 20;

/// The diagonal of a 6x6 covariance stored as its 21-entry upper-right triangle, row-major
/// (COVARIANCE_MATRIX_X_VARIANCE = 0, _Y_ = 6, _Z_ = 11, _ROLL_ = 15, _PITCH_ = 18, _YAW_ = 20;
/// the same indices for vx..yawrate). MAVLink's ODOMETRY uses the same layout.
inline constexpr std::size_t kCovarianceDiagonal[6] = {0, 6, 11, 15, 18, 20};
inline constexpr std::size_t kCovarianceLen = 21;

/// VIO_MAX_REPORTED_FEATURES: length of ext_vio_data_t.features.
inline constexpr std::size_t kVioMaxReportedFeatures = 64;

/// VIO_RECOMMENDED_PIPE_SIZE (64 KiB): the hitl_vio pipe size; 200 records, 0.8 s at 250 Hz.
inline constexpr int kVioRecommendedPipeSize_bytes = 64 * 1024;

#pragma pack(push, 1)
/// vio_data_t, `__attribute__((packed))`.
struct VioData {
  uint32_t magic_number;           ///< kVioMagicNumber
  int32_t quality;                 ///< > 0 in normal use, larger is better; -1 when failed
  int64_t timestamp_ns;            ///< CLOCK_MONOTONIC of the pose
  float T_imu_wrt_vio[3];          ///< m
  float R_imu_to_vio[3][3];        ///< row-major
  float pose_covariance[21];       ///< x, y, z, roll, pitch, yaw; upper-right triangle
  float vel_imu_wrt_vio[3];        ///< m/s
  float velocity_covariance[21];   ///< vx, vy, vz, rollspeed, pitchspeed, yawspeed
  float imu_angular_vel[3];        ///< rad/s about the IMU's x, y, z
  float gravity_vector[3];         ///< in the VIO frame
  float T_cam_wrt_imu[3];          ///< m
  float R_cam_to_imu[3][3];
  uint32_t error_code;             ///< ERROR_CODE_* bits
  uint16_t n_feature_points;
  uint8_t state;                   ///< kVioState*
  uint8_t frame;                   ///< kVioFrame* (`reserved` in the 2022 header)
};
#pragma pack(pop)

/// vio_point_quality_t: a C enum, int-sized.
enum VioPointQuality : int32_t { kPointQualityLow = 0, kPointQualityMedium = 1, kPointQualityHigh = 2 };

/// vio_feature_t: NOT packed in ModalAI's header; every member is 4 bytes, so there is no padding.
struct VioFeature {
  uint32_t id;
  int32_t cam_id;
  float pix_loc[2];
  float tsf[3];
  float p_tsf[3][3];
  float depth;
  float depth_error_stddev;
  VioPointQuality point_quality;
};

#pragma pack(push, 1)
/// ext_vio_data_t, `__attribute__((packed))`: vio_data_t plus the estimator's internals.
struct ExtVioData {
  VioData v;
  int32_t last_cam_frame_id;
  int64_t last_cam_timestamp_ns;
  float imu_cam_time_shift_s;
  float gravity_covariance[3][3];
  float gyro_bias[3];
  float accl_bias[3];
  uint32_t n_total_features;
  VioFeature features[kVioMaxReportedFeatures];
};
#pragma pack(pop)

// The layout, pinned: "totals 324 bytes" / "totals 5268 bytes" in ModalAI's header.
static_assert(sizeof(VioData) == 324);
static_assert(offsetof(VioData, magic_number) == 0);
static_assert(offsetof(VioData, quality) == 4);
static_assert(offsetof(VioData, timestamp_ns) == 8);
static_assert(offsetof(VioData, T_imu_wrt_vio) == 16);
static_assert(offsetof(VioData, R_imu_to_vio) == 28);
static_assert(offsetof(VioData, pose_covariance) == 64);
static_assert(offsetof(VioData, vel_imu_wrt_vio) == 148);
static_assert(offsetof(VioData, velocity_covariance) == 160);
static_assert(offsetof(VioData, imu_angular_vel) == 244);
static_assert(offsetof(VioData, gravity_vector) == 256);
static_assert(offsetof(VioData, T_cam_wrt_imu) == 268);
static_assert(offsetof(VioData, R_cam_to_imu) == 280);
static_assert(offsetof(VioData, error_code) == 316);
static_assert(offsetof(VioData, n_feature_points) == 320);
static_assert(offsetof(VioData, state) == 322);
static_assert(offsetof(VioData, frame) == 323);

static_assert(sizeof(VioPointQuality) == 4);
static_assert(sizeof(VioFeature) == 76);
static_assert(offsetof(VioFeature, cam_id) == 4);
static_assert(offsetof(VioFeature, pix_loc) == 8);
static_assert(offsetof(VioFeature, tsf) == 16);
static_assert(offsetof(VioFeature, p_tsf) == 28);
static_assert(offsetof(VioFeature, depth) == 64);
static_assert(offsetof(VioFeature, depth_error_stddev) == 68);
static_assert(offsetof(VioFeature, point_quality) == 72);

static_assert(sizeof(ExtVioData) == 5268);
static_assert(offsetof(ExtVioData, v) == 0);
static_assert(offsetof(ExtVioData, last_cam_frame_id) == 324);
static_assert(offsetof(ExtVioData, last_cam_timestamp_ns) == 328);
static_assert(offsetof(ExtVioData, imu_cam_time_shift_s) == 336);
static_assert(offsetof(ExtVioData, gravity_covariance) == 340);
static_assert(offsetof(ExtVioData, gyro_bias) == 376);
static_assert(offsetof(ExtVioData, accl_bias) == 388);
static_assert(offsetof(ExtVioData, n_total_features) == 400);
static_assert(offsetof(ExtVioData, features) == 404);

}  // namespace hitl::vio
