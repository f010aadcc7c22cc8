// dsp_hitl: the spec's DSP-side HITL shim. Takes hil_sensor_imu and hil_sensor_mag_baro (published
// by the patched MavlinkReceiver on the apps processor, carried over MUORB) and republishes them as
// PX4's sensor_accel + sensor_gyro (1310988), sensor_mag (197388) and sensor_baro (6620172) with
// fresh timestamps. The logic (device IDs, timestamps, what is dropped and counted, the status text)
// is target/core's DspHitl; this module polls, converts and publishes.
//
// Polling: px4_poll() on both topics with a 4 ms timeout (250 Hz), so each publication is handled
// as it arrives. A fixed 4 ms sleep, as the spec describes it, would poll a 4 ms topic whose queue
// holds one message: whenever the two 4 ms phases meet, a sample is lost and the next one read twice.
#pragma once

#include <pthread.h>

#include <drivers/drv_hrt.h>
#include <px4_platform_common/module.h>
#include <uORB/PublicationMulti.hpp>
#include <uORB/topics/sensor_accel.h>
#include <uORB/topics/sensor_baro.h>
#include <uORB/topics/sensor_gyro.h>
#include <uORB/topics/sensor_mag.h>

#include "target/core/dsp_hitl.h"

class DspHitlModule : public ModuleBase<DspHitlModule>
{
public:
	/** The poll timeout: the spec's 250 Hz. */
	static constexpr int kPollTimeout_ms = 4;

	DspHitlModule();
	~DspHitlModule() override;

	/** @see ModuleBase */
	static int task_spawn(int argc, char *argv[]);
	/** @see ModuleBase */
	static DspHitlModule *instantiate(int argc, char *argv[]);
	/** @see ModuleBase */
	static int custom_command(int argc, char *argv[]);
	/** @see ModuleBase */
	static int print_usage(const char *reason = nullptr);

	/** `dsp_hitl status` when not running: the spec's text with "Running: no". */
	static int print_stopped_status();

	/** @see ModuleBase::run */
	void run() override;

	/** `dsp_hitl status`: the spec's text (base/contract/dsp_hitl_status.h). */
	int print_status() override;

private:
	void republish_imu(int subscription, hrt_abstime now_us);
	void republish_mag_baro(int subscription, hrt_abstime now_us);

	hitl::target::DspHitl _dsp;
	pthread_mutex_t _dsp_mutex; ///< _dsp is read by `status` from the shell's thread

	uORB::PublicationMulti<sensor_accel_s>	_sensor_accel_pub{ORB_ID(sensor_accel)};
	uORB::PublicationMulti<sensor_gyro_s>	_sensor_gyro_pub{ORB_ID(sensor_gyro)};
	uORB::PublicationMulti<sensor_mag_s>	_sensor_mag_pub{ORB_ID(sensor_mag)};
	uORB::PublicationMulti<sensor_baro_s>	_sensor_baro_pub{ORB_ID(sensor_baro)};
};
