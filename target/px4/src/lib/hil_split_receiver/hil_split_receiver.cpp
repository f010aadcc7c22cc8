#include "hil_split_receiver.hpp"

#include <px4_platform_common/px4_config.h> // board_config.h: PX4_SOC_ARCH_ID

#include <hitl_target_core/uorb_conversions.hpp>

#include "target/core/hil_gps.h"
#include "target/core/hil_inputs.h"
#include "target/core/hil_split.h"

#ifndef HITL_HIL_SPLIT_ANY_BOARD
#define HITL_HIL_SPLIT_ANY_BOARD 0
#endif

namespace hitl_px4
{

namespace
{

hitl::target::HilSensorInput to_input(const mavlink_hil_sensor_t &msg)
{
	hitl::target::HilSensorInput in;
	in.time_usec = msg.time_usec;
	in.accel_FRD_m_s2[0] = msg.xacc;
	in.accel_FRD_m_s2[1] = msg.yacc;
	in.accel_FRD_m_s2[2] = msg.zacc;
	in.gyro_FRD_rad_s[0] = msg.xgyro;
	in.gyro_FRD_rad_s[1] = msg.ygyro;
	in.gyro_FRD_rad_s[2] = msg.zgyro;
	in.mag_FRD_gauss[0] = msg.xmag;
	in.mag_FRD_gauss[1] = msg.ymag;
	in.mag_FRD_gauss[2] = msg.zmag;
	in.abs_pressure_hPa = msg.abs_pressure;
	in.diff_pressure_hPa = msg.diff_pressure;
	in.pressure_alt_m = msg.pressure_alt;
	in.temperature_degC = msg.temperature;
	in.fields_updated = msg.fields_updated;
	in.id = msg.id;
	return in;
}

hitl::target::HilGpsInput to_input(const mavlink_hil_gps_t &msg)
{
	hitl::target::HilGpsInput in;
	in.time_usec = msg.time_usec;
	in.fix_type = msg.fix_type;
	in.lat_degE7 = msg.lat;
	in.lon_degE7 = msg.lon;
	in.alt_mm = msg.alt;
	in.eph_cm = msg.eph;
	in.epv_cm = msg.epv;
	in.vel_cm_s = msg.vel;
	in.vn_cm_s = msg.vn;
	in.ve_cm_s = msg.ve;
	in.vd_cm_s = msg.vd;
	in.cog_cdeg = msg.cog;
	in.satellites_visible = msg.satellites_visible;
	in.id = msg.id;
	return in;
}

} // namespace

bool hil_split_enabled()
{
	static constexpr bool voxl2_apps_processor = (PX4_SOC_ARCH_ID == PX4_SOC_ARCH_ID_VOXL2);
	static constexpr bool any_board = (HITL_HIL_SPLIT_ANY_BOARD != 0);
	return voxl2_apps_processor || any_board;
}

HilSplitReceiver::HilSplitReceiver() :
	_split(new hitl::target::HilSplit(hitl::target::HilSplitConfig{}))
{
}

HilSplitReceiver::~HilSplitReceiver()
{
	delete _split;
}

void HilSplitReceiver::handle_hil_sensor(const mavlink_hil_sensor_t &msg, hrt_abstime now_us)
{
	if (_split != nullptr) {
		_split->on_hil_sensor(to_input(msg), now_us);
	}
}

void HilSplitReceiver::handle_hil_gps(const mavlink_hil_gps_t &msg, hrt_abstime now_us)
{
	_sensor_gps_pub.publish(to_uorb(hitl::target::to_sensor_gps(to_input(msg), now_us)));
}

void HilSplitReceiver::publish_due(hrt_abstime now_us)
{
	if (_split == nullptr) {
		return;
	}

	const hitl::target::HilSplitOutput out = _split->poll(now_us);

	if (out.imu) {
		_hil_sensor_imu_pub.publish(to_uorb(*out.imu));
	}

	if (out.mag_baro) {
		_hil_sensor_mag_baro_pub.publish(to_uorb(*out.mag_baro));
	}

	if (out.battery) {
		_battery_status_pub.publish(to_uorb(*out.battery));
	}
}

int HilSplitReceiver::poll_timeout_ms(hrt_abstime now_us, int max_timeout_ms) const
{
	return (_split != nullptr) ? _split->poll_timeout_ms(now_us, max_timeout_ms) : max_timeout_ms;
}

} // namespace hitl_px4
