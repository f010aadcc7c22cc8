// What PX4's MavlinkReceiver calls for the spec's VOXL2 HIL split (the patch in
// target/px4/patches/): HIL_SENSOR goes into target/core's HilSplit instead of straight to
// sensor_accel/gyro/mag/baro, and HilSplitReceiver publishes
//   hil_sensor_imu       every 4000 us   (for dsp_hitl on the DSP, over MUORB)
//   hil_sensor_mag_baro  every 10000 us  (fields_updated: FIELD_MAG, FIELD_BARO)
//   battery_status       every 100 ms    (the simulated 16.8 V / 5.0 A / 100 % battery)
// while HIL_SENSOR keeps arriving, and HIL_GPS -> sensor_gps per message. The logic is
// target/core's (docs/target-core.md); this class only converts and publishes.
//
// This header is included by mavlink_receiver.h, which PX4 v1.16 compiles as gnu++14, so it uses
// no C++17 and keeps target/core (C++17) behind a pointer.
#pragma once

#include <stdint.h>

#include <drivers/drv_hrt.h>
#include <mavlink/mavlink_bridge_header.h>
#include <uORB/Publication.hpp>
#include <uORB/PublicationMulti.hpp>
#include <uORB/topics/battery_status.h>
#include <uORB/topics/hil_sensor_imu.h>
#include <uORB/topics/hil_sensor_mag_baro.h>
#include <uORB/topics/sensor_gps.h>

namespace hitl
{
namespace target
{
class HilSplit;
} // namespace target
} // namespace hitl

namespace hitl_px4
{

/**
 * The spec's gate: the split replaces MavlinkReceiver's HIL_SENSOR and HIL_GPS handling on the
 * VOXL2 apps processor (PX4_SOC_ARCH_ID == PX4_SOC_ARCH_ID_VOXL2), or on any board built with
 * HITL_HIL_SPLIT_ANY_BOARD=ON (PX4 SITL with dsp_hitl in the loop).
 *
 * Compared in C++, not with #if: PX4_SOC_ARCH_ID_* are enum constants, which the preprocessor
 * reads as 0, so the spec's `#if PX4_SOC_ARCH_ID == PX4_SOC_ARCH_ID_VOXL2` is true on every board.
 */
bool hil_split_enabled();

class HilSplitReceiver
{
public:
	HilSplitReceiver();
	~HilSplitReceiver();
	HilSplitReceiver(const HilSplitReceiver &) = delete;
	HilSplitReceiver &operator=(const HilSplitReceiver &) = delete;

	/** One HIL_SENSOR that arrived at now_us; what it contributes goes out with publish_due(). */
	void handle_hil_sensor(const mavlink_hil_sensor_t &msg, hrt_abstime now_us);

	/** One HIL_GPS that arrived at now_us: published as sensor_gps at once (not batched). */
	void handle_hil_gps(const mavlink_hil_gps_t &msg, hrt_abstime now_us);

	/** Publishes hil_sensor_imu, hil_sensor_mag_baro and battery_status that are due at now_us. */
	void publish_due(hrt_abstime now_us);

	/** How long the receive loop may block in poll(), ms (HilSplit::poll_timeout_ms). */
	int poll_timeout_ms(hrt_abstime now_us, int max_timeout_ms) const;

private:
	hitl::target::HilSplit *_split{nullptr}; // target/core, C++17: kept out of this header

	uORB::Publication<hil_sensor_imu_s>		_hil_sensor_imu_pub{ORB_ID(hil_sensor_imu)};
	uORB::Publication<hil_sensor_mag_baro_s>	_hil_sensor_mag_baro_pub{ORB_ID(hil_sensor_mag_baro)};
	uORB::Publication<battery_status_s>		_battery_status_pub{ORB_ID(battery_status)};
	uORB::PublicationMulti<sensor_gps_s>		_sensor_gps_pub{ORB_ID(sensor_gps)};
};

} // namespace hitl_px4
