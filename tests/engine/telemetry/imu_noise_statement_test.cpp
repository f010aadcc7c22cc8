// The simulator's statement of its IMU's noise (engine/telemetry/imu_noise_statement.h): what it
// writes reads back, and any other text, or a damaged one, is not taken for it.
#include <gtest/gtest.h>

#include "engine/telemetry/imu_noise_statement.h"

namespace hitl::telemetry {
namespace {

TEST(ImuNoiseStatement, ReadsBackWhatItSays) {
  const ImuNoiseFigures f{"icm-42688-p", 4.886921905584123e-05, 0.0, 6.864655e-04, 4e-4};
  const std::string text = imu_noise_statement(f);
  EXPECT_EQ(text, "imu noise (profile icm-42688-p): gyro N 4.8869e-05 rad/s/sqrt(Hz) B 0 rad/s, accel N 0.00068647 "
                  "m/s^2/sqrt(Hz) B 0.0004 m/s^2");
  const auto back = parse_imu_noise_statement(text);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->profile, "icm-42688-p");
  EXPECT_NEAR(back->gyro_noise_density, f.gyro_noise_density, 1e-9);
  EXPECT_EQ(back->gyro_bias_instability, 0.0);
  EXPECT_NEAR(back->accel_noise_density, f.accel_noise_density, 1e-8);
  EXPECT_EQ(back->accel_bias_instability, 4e-4);
  const auto unnamed = parse_imu_noise_statement(imu_noise_statement({"", 3.394e-4, 0, 0.004, 0}));
  ASSERT_TRUE(unnamed.has_value());
  EXPECT_EQ(unnamed->profile, "");
  EXPECT_EQ(unnamed->accel_noise_density, 0.004);
}

TEST(ImuNoiseStatement, OtherOrDamagedTextIsNotTakenForIt) {
  const std::string good = imu_noise_statement({"generic", 3.394e-4, 0, 0.004, 0});
  for (const std::string& text :
       {std::string("t=15.000 s fault gps-loss started (3 s)"), std::string(""), good.substr(0, good.size() - 1), good + " ",
        std::string("imu noise (profile Generic): gyro N 1 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise (profile ): gyro N 1 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise: gyro N -1 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise: gyro N nan rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise: gyro N 1e999 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise: gyro N 1.79769e308 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        std::string("imu noise: gyro N 1e-5e3 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"),
        "imu noise (profile " + std::string(65, 'a') + "): gyro N 1 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"})
    EXPECT_FALSE(parse_imu_noise_statement(text).has_value()) << text;
}

}  // namespace
}  // namespace hitl::telemetry
