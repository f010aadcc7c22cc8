#include "uorb_conversions.hpp"

#include <algorithm>

namespace hitl_px4
{

namespace
{

template <typename From, typename To>
void copy3(const From (&from)[3], To (&to)[3])
{
	std::copy(from, from + 3, to);
}

} // namespace

// The .msg files and core's mirror must agree on the constants as they do on the fields.
static_assert(hil_sensor_mag_baro_s::FIELD_MAG == hitl::target::HilSensorMagBaro::FIELD_MAG,
	      "HilSensorMagBaro.msg FIELD_MAG and target/core/hil_uorb_messages.h differ");
static_assert(hil_sensor_mag_baro_s::FIELD_BARO == hitl::target::HilSensorMagBaro::FIELD_BARO,
	      "HilSensorMagBaro.msg FIELD_BARO and target/core/hil_uorb_messages.h differ");
static_assert(sizeof(hil_sensor_imu_s::accelerometer_m_s2) == sizeof(hitl::target::HilSensorImu::accelerometer_m_s2),
	      "HilSensorImu.msg accelerometer_m_s2 is not float32[3]");
static_assert(sizeof(hil_sensor_mag_baro_s::magnetometer_ga) == sizeof(hitl::target::HilSensorMagBaro::magnetometer_ga),
	      "HilSensorMagBaro.msg magnetometer_ga is not float32[3]");

hil_sensor_imu_s to_uorb(const hitl::target::HilSensorImu &in)
{
	hil_sensor_imu_s out{};
	out.timestamp = in.timestamp;
	copy3(in.accelerometer_m_s2, out.accelerometer_m_s2);
	copy3(in.gyroscope_rad_s, out.gyroscope_rad_s);
	out.temperature = in.temperature;
	return out;
}

hil_sensor_mag_baro_s to_uorb(const hitl::target::HilSensorMagBaro &in)
{
	hil_sensor_mag_baro_s out{};
	out.timestamp = in.timestamp;
	copy3(in.magnetometer_ga, out.magnetometer_ga);
	out.pressure_pa = in.pressure_pa;
	out.temperature = in.temperature;
	out.fields_updated = in.fields_updated;
	return out;
}

hitl::target::HilSensorImu from_uorb(const hil_sensor_imu_s &in)
{
	hitl::target::HilSensorImu out;
	out.timestamp = in.timestamp;
	copy3(in.accelerometer_m_s2, out.accelerometer_m_s2);
	copy3(in.gyroscope_rad_s, out.gyroscope_rad_s);
	out.temperature = in.temperature;
	return out;
}

hitl::target::HilSensorMagBaro from_uorb(const hil_sensor_mag_baro_s &in)
{
	hitl::target::HilSensorMagBaro out;
	out.timestamp = in.timestamp;
	copy3(in.magnetometer_ga, out.magnetometer_ga);
	out.pressure_pa = in.pressure_pa;
	out.temperature = in.temperature;
	out.fields_updated = in.fields_updated;
	return out;
}

sensor_accel_s to_uorb(const hitl::target::SensorAccel &in)
{
	sensor_accel_s out{};
	out.timestamp = in.timestamp_us;
	out.timestamp_sample = in.timestamp_sample_us;
	out.device_id = in.device_id;
	out.x = in.accel_FRD_m_s2[0];
	out.y = in.accel_FRD_m_s2[1];
	out.z = in.accel_FRD_m_s2[2];
	out.temperature = in.temperature_degC;
	out.samples = 1;
	return out;
}

sensor_gyro_s to_uorb(const hitl::target::SensorGyro &in)
{
	sensor_gyro_s out{};
	out.timestamp = in.timestamp_us;
	out.timestamp_sample = in.timestamp_sample_us;
	out.device_id = in.device_id;
	out.x = in.gyro_FRD_rad_s[0];
	out.y = in.gyro_FRD_rad_s[1];
	out.z = in.gyro_FRD_rad_s[2];
	out.temperature = in.temperature_degC;
	out.samples = 1;
	return out;
}

sensor_mag_s to_uorb(const hitl::target::SensorMag &in)
{
	sensor_mag_s out{};
	out.timestamp = in.timestamp_us;
	out.timestamp_sample = in.timestamp_sample_us;
	out.device_id = in.device_id;
	out.x = in.mag_FRD_gauss[0];
	out.y = in.mag_FRD_gauss[1];
	out.z = in.mag_FRD_gauss[2];
	out.temperature = in.temperature_degC;
	return out;
}

sensor_baro_s to_uorb(const hitl::target::SensorBaro &in)
{
	sensor_baro_s out{};
	out.timestamp = in.timestamp_us;
	out.timestamp_sample = in.timestamp_sample_us;
	out.device_id = in.device_id;
	out.pressure = in.pressure_Pa;
	out.temperature = in.temperature_degC;
	return out;
}

sensor_gps_s to_uorb(const hitl::target::SensorGps &in)
{
	sensor_gps_s out{};
	out.timestamp = in.timestamp_us;
	out.time_utc_usec = in.time_utc_us;
	out.device_id = in.device_id;
	out.latitude_deg = in.latitude_deg;
	out.longitude_deg = in.longitude_deg;
	out.altitude_msl_m = in.altitude_msl_m;
	out.altitude_ellipsoid_m = in.altitude_ellipsoid_m;
	out.s_variance_m_s = in.s_variance_m_s;
	out.c_variance_rad = in.c_variance_rad;
	out.eph = in.eph_m;
	out.epv = in.epv_m;
	out.vel_m_s = in.vel_m_s;
	out.vel_n_m_s = in.vel_n_m_s;
	out.vel_e_m_s = in.vel_e_m_s;
	out.vel_d_m_s = in.vel_d_m_s;
	out.cog_rad = in.cog_rad;
	out.heading = in.heading_rad;
	out.heading_offset = in.heading_offset_rad;
	out.vel_ned_valid = in.vel_ned_valid;
	out.fix_type = in.fix_type;
	out.satellites_used = in.satellites_used;
	return out;
}

battery_status_s to_uorb(const hitl::target::BatteryStatus &in)
{
	battery_status_s out{};
	out.timestamp = in.timestamp_us;
	out.connected = in.connected;
	out.voltage_v = in.voltage_V;
	out.current_a = in.current_A;
	out.current_average_a = in.current_average_A;
	out.discharged_mah = in.discharged_mAh;
	out.remaining = in.remaining_ratio;
	out.scale = in.scale;
	out.time_remaining_s = in.time_remaining_s;
	out.temperature = in.temperature_degC;
	out.cell_count = in.cell_count;
	out.source = in.source;
	out.id = in.id;
	out.warning = in.warning;
	return out;
}

} // namespace hitl_px4
