// Sensor profiles (engine/sensors/profiles/*.json): selected in the vehicle file, applied under the
// file's own keys, unknown names refused with the file and key; the IMU's quantisation, scale and
// cross-axis error; the bias instability model's Allan floor.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "engine/model/config_json.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/imu.h"
#include "engine/sensors/inertial_noise.h"
#include "engine/sensors/magnetometer.h"
#include "engine/sensors/sensor_profiles.h"
#include "engine/sensors/vehicle_file.h"
#include "engine/telemetry/allan_deviation.h"

namespace hitl::sensors {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SensorProfiles, EveryProfileParsesAndNamesItsPartAndSources) {
  EXPECT_EQ(imu_profile_names(), (std::vector<std::string>{"generic", "icm-42688-p"}));
  for (const std::string& name : imu_profile_names()) {
    auto info = imu_profile_info(name);
    ASSERT_TRUE(info.ok()) << name;
    EXPECT_EQ(info->name, name);
    EXPECT_EQ(info->kind, "imu");
    EXPECT_FALSE(info->part.empty());
    EXPECT_FALSE(info->sources.empty());
    EXPECT_TRUE(apply_imu_profile(name, model::x500_vehicle_config()).ok()) << name;
  }
}

TEST(SensorProfiles, EveryKindHasGenericAndItsBoardPart) {
  EXPECT_EQ(profile_names("baro"), (std::vector<std::string>{"generic", "icp-10100"}));
  EXPECT_EQ(profile_names("mag"), (std::vector<std::string>{"generic", "ist8310"}));
  EXPECT_EQ(profile_names("gps"), (std::vector<std::string>{"generic", "u-blox-m10"}));
  for (std::string_view kind : kProfileKinds) {
    for (const std::string& name : profile_names(kind)) {
      auto info = profile_info(kind, name);
      ASSERT_TRUE(info.ok()) << kind << " " << name;
      EXPECT_EQ(info->name, name);
      EXPECT_EQ(info->kind, kind);
      EXPECT_FALSE(info->part.empty());
      EXPECT_FALSE(info->sources.empty());
      auto applied = apply_profile(kind, name, model::x500_vehicle_config());
      EXPECT_TRUE(applied.ok()) << kind << " " << name << ": " << (applied ? "" : applied.error().message);
      // generic is the compiled-in x500's values, byte for byte.
      if (name == "generic") {
        EXPECT_EQ(model::to_json_text(*applied), model::to_json_text(model::x500_vehicle_config())) << kind;
      }
    }
  }
}

TEST(SensorProfiles, Icp10100CarriesTheDatasheetNoise) {
  auto file = parse_vehicle_file(R"({"sensors": {"baro": {"profile": "icp-10100"}}})", "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->baro_profile, "icp-10100");
  EXPECT_EQ(file->vehicle.sensors.baro.noise_pa, 0.4);  // DS-000186: 0.4 Pa RMS in ULN mode, PX4's
  EXPECT_EQ(file->vehicle.sensors.baro.drift_pa_sqrt_s, 0.0);  // not published: generic
  EXPECT_EQ(file->vehicle.sensors.baro.rate_hz, 10.0);  // the HIL rate stays the vehicle's
  EXPECT_EQ(file->imu_profile, "generic");
}

TEST(SensorProfiles, Ist8310CarriesPx4sResolutionAndTheGenericNoise) {
  auto file = parse_vehicle_file(R"({"sensors": {"mag": {"profile": "ist8310"}}})", "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  const model::MagConfig& mag = file->vehicle.sensors.mag;
  EXPECT_DOUBLE_EQ(mag.resolution_gauss, 1.0 / 1320.0);  // 16-bit output, 1320 LSB/gauss
  EXPECT_EQ(mag.range_gauss, 0.0);
  EXPECT_EQ(mag.noise.noise_density, model::x500_vehicle_config().sensors.mag.noise.noise_density);
  Magnetometer m(mag, model::default_world_config().magnetic_field, 4);
  model::VehicleState s;
  for (int k = 1; k <= 50; ++k) {
    const Eigen::Vector3d b = m.sample(s, 0.02 * k).mag_FRD_gauss;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(b[i] * 1320.0, std::round(b[i] * 1320.0), 1e-9);
  }
}

TEST(SensorProfiles, UbloxM10CarriesItsCepAndVelocityAccuracy) {
  auto file = parse_vehicle_file(R"({"sensors": {"gps": {"profile": "u-blox-m10"}}})", "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  const model::GpsConfig& gps = file->vehicle.sensors.gps;
  EXPECT_NEAR(gps.horizontal_error_sigma_m * 1.1774, 1.5, 0.001);  // 1.5 m CEP
  EXPECT_NEAR(gps.vertical_error_sigma_m / gps.horizontal_error_sigma_m, 15.0 / 9.0, 0.001);  // SPS PS: 15 m / 9 m
  EXPECT_EQ(gps.error_correlation_time_s, 60.0);
  EXPECT_EQ(gps.velocity_noise_m_s, 0.05);
  EXPECT_TRUE(gps.accuracy_follows_error);
  EXPECT_EQ(gps.rate_hz, 30.0);
}

TEST(SensorProfiles, AllFourReadBackAsWrittenAndAreRefusedByName) {
  auto file = parse_vehicle_file(R"({"sensors": {"imu": {"profile": "icm-42688-p"}, "baro": {"profile": "icp-10100"},
                                     "mag": {"profile": "ist8310"}, "gps": {"profile": "u-blox-m10", "satellites": 14}}})",
                                 "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->vehicle.sensors.gps.satellites, 14);  // the file's own key over the profile
  auto again = parse_vehicle_file(to_json_text(*file), "again.json");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(to_json_text(*again), to_json_text(*file));
  EXPECT_EQ(again->gps_profile, "u-blox-m10");
  EXPECT_EQ(again->mag_profile, "ist8310");
  auto unknown = parse_vehicle_file(R"({"sensors": {"baro": {"profile": "bmp388"}}})", "v.json");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message, "v.json: sensors.baro.profile: unknown barometer profile \"bmp388\" (known: generic, icp-10100)");
  auto number = parse_vehicle_file(R"({"sensors": {"gps": {"profile": 9}}})", "v.json");
  ASSERT_FALSE(number.ok());
  EXPECT_EQ(number.error().message, "v.json: sensors.gps.profile: must be a string, one of: generic, u-blox-m10 (got 9)");
}

TEST(SensorProfiles, GenericIsTheDefaultAndChangesNothing) {
  const model::VehicleConfig x500 = model::x500_vehicle_config();
  auto generic = apply_imu_profile("generic", x500);
  ASSERT_TRUE(generic.ok()) << generic.error().message;
  EXPECT_EQ(model::to_json_text(*generic), model::to_json_text(x500));
  auto file = parse_vehicle_file("{}", "vehicle.json");
  ASSERT_TRUE(file.ok());
  EXPECT_EQ(file->imu_profile, "generic");
}

TEST(SensorProfiles, Icm42688pCarriesTheDatasheetFigures) {
  auto file = parse_vehicle_file(R"({"sensors": {"imu": {"profile": "icm-42688-p"}}})", "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  const model::ImuConfig& imu = file->vehicle.sensors.imu;
  EXPECT_EQ(file->imu_profile, "icm-42688-p");
  EXPECT_NEAR(imu.gyro.noise_density, 2.8e-3 * kPi / 180.0, 1e-12);  // 2.8 mdps/sqrt(Hz)
  EXPECT_NEAR(imu.accel.noise_density, 70e-6 * 9.80665, 1e-12);     // 70 ug/sqrt(Hz)
  EXPECT_DOUBLE_EQ(imu.gyro_resolution_rad_s, imu.gyro_range_rad_s / 32768.0);
  EXPECT_DOUBLE_EQ(imu.accel_resolution_m_s2, imu.accel_range_m_s2 / 32768.0);
  EXPECT_EQ(imu.rate_hz, 250.0);  // the HIL rate is the vehicle's, not the profile's
  // It reads back as written.
  auto again = parse_vehicle_file(to_json_text(*file), "again.json");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(to_json_text(*again), to_json_text(*file));
}

TEST(SensorProfiles, TheFilesOwnKeysApplyOverTheProfile) {
  auto file = parse_vehicle_file(
      R"({"sensors": {"imu": {"gyro": {"bias_instability": 1e-4}, "profile": "icm-42688-p"}}})", "vehicle.json");
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->vehicle.sensors.imu.gyro.bias_instability, 1e-4);
  EXPECT_NEAR(file->vehicle.sensors.imu.gyro.noise_density, 4.8869e-5, 1e-9);
}

TEST(SensorProfiles, UnknownOrMistypedProfileIsRefusedWithFileAndKey) {
  auto unknown = parse_vehicle_file(R"({"sensors": {"imu": {"profile": "mpu-6000"}}})", "v.json");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message,
            "v.json: sensors.imu.profile: unknown IMU profile \"mpu-6000\" (known: generic, icm-42688-p)");
  auto number = parse_vehicle_file(R"({"sensors": {"imu": {"profile": 3}}})", "v.json");
  ASSERT_FALSE(number.ok());
  EXPECT_EQ(number.error().message, "v.json: sensors.imu.profile: must be a string, one of: generic, icm-42688-p (got 3)");
}

TEST(SensorProfiles, TheExampleVehicleFilesLoad) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(HITL_SOURCE_DIR) + "/docs/examples/vehicles")) {
    auto file = load_vehicle_file(entry.path());
    EXPECT_TRUE(file.ok()) << entry.path() << ": " << (file ? "" : file.error().message);
    ++n;
  }
  EXPECT_GE(n, 1u);
  auto icm = load_vehicle_file(std::string(HITL_SOURCE_DIR) + "/docs/examples/vehicles/x500-voxl2-icm-42688-p.json");
  ASSERT_TRUE(icm.ok());
  EXPECT_EQ(icm->imu_profile, "icm-42688-p");
}

model::VehicleState at_rest() {
  model::VehicleState s;
  s.specific_force_FLU_m_s2 = {0.0, 0.0, 9.80665};
  s.w_step_mean_FLU_rad_s = {0.01, -0.02, 0.003};
  return s;
}

TEST(ImuResolution, ReadingsAreWholeCountsOfTheLsb) {
  auto profile = apply_imu_profile("icm-42688-p", model::x500_vehicle_config());
  ASSERT_TRUE(profile.ok());
  const model::ImuConfig& config = profile->sensors.imu;
  Imu imu(config, model::default_world_config(), 5);
  for (int k = 1; k <= 100; ++k) {
    const ImuSample s = imu.sample(at_rest(), 0.004 * k);
    for (int i = 0; i < 3; ++i) {
      const double counts_gyro = s.gyro_FRD_rad_s[i] / config.gyro_resolution_rad_s;
      const double counts_accel = s.accel_FRD_m_s2[i] / config.accel_resolution_m_s2;
      EXPECT_NEAR(counts_gyro, std::round(counts_gyro), 1e-6);
      EXPECT_NEAR(counts_accel, std::round(counts_accel), 1e-6);
    }
  }
}

TEST(InertialNoise, ScaleAndCrossAxisErrorsMultiplyTheTruth) {
  model::InertialNoiseConfig config;
  config.bias_correlation_time_s = 100.0;
  config.scale_error_sigma = 0.01;
  config.cross_axis_sigma = 0.005;
  InertialNoise noise(config, 250.0, 9, "imu.gyro");
  const Eigen::Matrix3d& m = noise.misalignment();
  EXPECT_NE(m, Eigen::Matrix3d::Identity());
  const Eigen::Vector3d truth(1.0, -2.0, 0.5);
  EXPECT_TRUE(noise.apply(truth, 0.004).isApprox(m * truth, 1e-15));
  // Without them M is the identity and draws nothing: the same bias stream as before.
  model::InertialNoiseConfig plain = config;
  plain.scale_error_sigma = plain.cross_axis_sigma = 0.0;
  EXPECT_EQ(InertialNoise(plain, 250.0, 9, "imu.gyro").misalignment(), Eigen::Matrix3d::Identity());
}

TEST(InertialNoise, BiasInstabilityGivesAnAllanFloorAtPoint664B) {
  // 10 minutes at 250 Hz with the ICM-42688-P's white noise and a bias instability of 10 deg/h.
  model::InertialNoiseConfig config;
  config.noise_density = 4.887e-5;
  config.bias_correlation_time_s = 1000.0;
  config.bias_instability = 10.0 / 3600.0 * kPi / 180.0;
  InertialNoise noise(config, 250.0, 21, "imu.gyro");
  std::vector<double> x(150000);
  for (double& v : x) v = noise.apply(Eigen::Vector3d::Zero(), 0.004).x();
  const telemetry::AllanFit fit = telemetry::fit_allan(telemetry::overlapping_allan_deviation(x, 250.0));
  EXPECT_NEAR(fit.noise_density / config.noise_density, 1.0, 0.2);
  EXPECT_NEAR(fit.bias_instability / config.bias_instability, 1.0, 0.5);
}

}  // namespace
}  // namespace hitl::sensors
