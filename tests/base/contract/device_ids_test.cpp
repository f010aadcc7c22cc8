#include "base/contract/device_ids.h"

#include <gtest/gtest.h>

namespace hitl::target {
namespace {

struct Decoded {
  unsigned bus_type, bus, address, devtype;
};

// Decodes as PX4's DeviceId union does (bus_type:3, bus:5, address:8, devtype:8, LSB first).
Decoded decode(uint32_t id) { return {id & 0x7U, (id >> 3) & 0x1FU, (id >> 8) & 0xFFU, (id >> 16) & 0xFFU}; }

TEST(DeviceIds, AreTheSpecsValues) {
  EXPECT_EQ(kDeviceIdImu, 1310988U);
  EXPECT_EQ(kDeviceIdMag, 197388U);
  EXPECT_EQ(kDeviceIdBaro, 6620172U);
  EXPECT_EQ(kDeviceIdGps, 11468804U);
}

TEST(DeviceIds, DecodeAsPx4DeviceId) {
  const Decoded imu = decode(1310988);
  EXPECT_EQ(imu.bus_type, 4U);  // SIMULATION
  EXPECT_EQ(imu.bus, 1U);
  EXPECT_EQ(imu.address, 0x01U);
  EXPECT_EQ(imu.devtype, 0x14U);  // DRV_IMU_DEVTYPE_SIM

  const Decoded mag = decode(197388);
  EXPECT_EQ(mag.bus_type, 4U);
  EXPECT_EQ(mag.bus, 1U);
  EXPECT_EQ(mag.address, 0x03U);
  EXPECT_EQ(mag.devtype, 0x03U);  // DRV_MAG_DEVTYPE_MAGSIM

  const Decoded baro = decode(6620172);
  EXPECT_EQ(baro.bus_type, 4U);
  EXPECT_EQ(baro.bus, 1U);
  EXPECT_EQ(baro.address, 0x04U);
  EXPECT_EQ(baro.devtype, 0x65U);  // DRV_BARO_DEVTYPE_BAROSIM

  const Decoded gps = decode(11468804);
  EXPECT_EQ(gps.bus_type, 4U);
  EXPECT_EQ(gps.bus, 0U);
  EXPECT_EQ(gps.address, 0x00U);
  EXPECT_EQ(gps.devtype, 0xAFU);  // DRV_GPS_DEVTYPE_SIM
}

TEST(DeviceIds, MakeDeviceIdPacksEachField) {
  EXPECT_EQ(make_device_id(DeviceBusType::I2C, 0, 0, 0), 1U);
  EXPECT_EQ(make_device_id(DeviceBusType::Unknown, 1, 0, 0), 1U << 3);
  EXPECT_EQ(make_device_id(DeviceBusType::Unknown, 31, 0, 0), 31U << 3);
  EXPECT_EQ(make_device_id(DeviceBusType::Unknown, 0, 0xAB, 0), 0xABU << 8);
  EXPECT_EQ(make_device_id(DeviceBusType::Unknown, 0, 0, 0xCD), 0xCDU << 16);
  // PX4's documented example: HMC5883 (0x01), SPI (2) bus 1, slot 5 = 66826.
  EXPECT_EQ(make_device_id(DeviceBusType::SPI, 1, 5, 0x01), 66826U);
}

}  // namespace
}  // namespace hitl::target
