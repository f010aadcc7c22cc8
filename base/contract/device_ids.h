// PX4 device IDs of the simulated sensors dsp_hitl publishes, defined once.
//
// A PX4 device_id is device::Device::DeviceId (src/lib/drivers/device/Device.hpp): a union of a
// uint32 with the bit fields, least significant first,
//   bus_type : 3   (DeviceBusType: 0 unknown, 1 I2C, 2 SPI, 3 UAVCAN, 4 SIMULATION, 5 SERIAL)
//   bus      : 5   (which instance of the bus type)
//   address  : 8   (address on the bus)
//   devtype  : 8   (DRV_*_DEVTYPE_* of src/drivers/drv_sensor.h)
// so device_id = devtype << 16 | address << 8 | bus << 3 | bus_type.
//
//   1310988  = 0x14010C: devtype 0x14 DRV_IMU_DEVTYPE_SIM,      address 0x01, bus 1, SIMULATION
//   197388   = 0x03030C: devtype 0x03 DRV_MAG_DEVTYPE_MAGSIM,   address 0x03, bus 1, SIMULATION
//   6620172  = 0x65040C: devtype 0x65 DRV_BARO_DEVTYPE_BAROSIM, address 0x04, bus 1, SIMULATION
//   11468804 = 0xAF0004: devtype 0xAF DRV_GPS_DEVTYPE_SIM,      address 0x00, bus 0, SIMULATION
// (0x0C = 0b00001'100: bus 1, bus_type 4.) The first three are the spec's dsp_hitl IDs and PX4
// SimulatorMavlink's first accel/gyro, mag and baro; the calibration parameters CAL_ACC0_ID,
// CAL_GYRO0_ID and CAL_MAG0_ID must equal them. The GPS ID is SimulatorMavlink's first GPS.
#pragma once

#include <cstdint>

namespace hitl::target {

/// device::Device::DeviceBusType values used here.
enum class DeviceBusType : uint8_t { Unknown = 0, I2C = 1, SPI = 2, UAVCAN = 3, Simulation = 4, Serial = 5 };

/// Packs the DeviceId bit fields (see above) into the uint32 PX4 stores.
constexpr uint32_t make_device_id(DeviceBusType bus_type, uint8_t bus, uint8_t address, uint8_t devtype) {
  return static_cast<uint32_t>(devtype) << 16 | static_cast<uint32_t>(address) << 8 |
         static_cast<uint32_t>(bus & 0x1FU) << 3 | (static_cast<uint32_t>(bus_type) & 0x07U);
}

/// drv_sensor.h device types.
inline constexpr uint8_t kDevtypeImuSim = 0x14;   ///< DRV_IMU_DEVTYPE_SIM
inline constexpr uint8_t kDevtypeMagSim = 0x03;   ///< DRV_MAG_DEVTYPE_MAGSIM
inline constexpr uint8_t kDevtypeBaroSim = 0x65;  ///< DRV_BARO_DEVTYPE_BAROSIM
inline constexpr uint8_t kDevtypeGpsSim = 0xAF;   ///< DRV_GPS_DEVTYPE_SIM

/// sensor_accel and sensor_gyro (one simulated IMU).
inline constexpr uint32_t kDeviceIdImu = make_device_id(DeviceBusType::Simulation, 1, 0x01, kDevtypeImuSim);
/// sensor_mag.
inline constexpr uint32_t kDeviceIdMag = make_device_id(DeviceBusType::Simulation, 1, 0x03, kDevtypeMagSim);
/// sensor_baro.
inline constexpr uint32_t kDeviceIdBaro = make_device_id(DeviceBusType::Simulation, 1, 0x04, kDevtypeBaroSim);
/// sensor_gps from HIL_GPS.
inline constexpr uint32_t kDeviceIdGps = make_device_id(DeviceBusType::Simulation, 0, 0x00, kDevtypeGpsSim);

static_assert(kDeviceIdImu == 1310988, "DRV_IMU_DEVTYPE_SIM, SIMULATION bus 1 address 1");
static_assert(kDeviceIdMag == 197388, "DRV_MAG_DEVTYPE_MAGSIM, SIMULATION bus 1 address 3");
static_assert(kDeviceIdBaro == 6620172, "DRV_BARO_DEVTYPE_BAROSIM, SIMULATION bus 1 address 4");
static_assert(kDeviceIdGps == 11468804, "DRV_GPS_DEVTYPE_SIM, SIMULATION bus 0 address 0");

}  // namespace hitl::target
