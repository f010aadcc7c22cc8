// The one place where target/core's plain structs meet PX4's generated uORB structs, field by
// field (the core struct's comments name the uORB field beside each member). Every uORB struct
// starts zero-initialised, so fields core does not fill (error_count, clip_counter, hdop, ...) are 0.
// C++17 (target/core); compiled only into hitl_target_core, dsp_hitl and hil_split_receiver.cpp.
#pragma once

#include <uORB/topics/battery_status.h>
#include <uORB/topics/hil_sensor_imu.h>
#include <uORB/topics/hil_sensor_mag_baro.h>
#include <uORB/topics/sensor_accel.h>
#include <uORB/topics/sensor_baro.h>
#include <uORB/topics/sensor_gps.h>
#include <uORB/topics/sensor_gyro.h>
#include <uORB/topics/sensor_mag.h>

#include "target/core/hil_uorb_messages.h"
#include "target/core/px4_topics.h"

namespace hitl_px4
{

// The spec's messages: to uORB on the apps processor, back from uORB on the DSP.
hil_sensor_imu_s to_uorb(const hitl::target::HilSensorImu &in);
hil_sensor_mag_baro_s to_uorb(const hitl::target::HilSensorMagBaro &in);
hitl::target::HilSensorImu from_uorb(const hil_sensor_imu_s &in);
hitl::target::HilSensorMagBaro from_uorb(const hil_sensor_mag_baro_s &in);

// PX4's own topics that core produces.
sensor_accel_s to_uorb(const hitl::target::SensorAccel &in);
sensor_gyro_s to_uorb(const hitl::target::SensorGyro &in);
sensor_mag_s to_uorb(const hitl::target::SensorMag &in);
sensor_baro_s to_uorb(const hitl::target::SensorBaro &in);
sensor_gps_s to_uorb(const hitl::target::SensorGps &in);
battery_status_s to_uorb(const hitl::target::BatteryStatus &in);

} // namespace hitl_px4
