#include "dsp_hitl.hpp"

#include <errno.h>
#include <string.h>

#include <hitl_target_core/uorb_conversions.hpp>
#include <px4_platform_common/log.h>
#include <px4_platform_common/posix.h>
#include <px4_platform_common/tasks.h>
#include <uORB/uORB.h>
#include <uORB/topics/hil_sensor_imu.h>
#include <uORB/topics/hil_sensor_mag_baro.h>

#include "base/contract/dsp_hitl_status.h"

namespace
{

/** Room for the whole status text (about 350 characters). */
constexpr size_t kStatusTextSize = 640;

/** PX4_INFO_RAW truncates at log_message_s::text (127 characters): the text goes out line by line. */
void print_lines(const char *text)
{
	while (*text != '\0') {
		const char *end = strchr(text, '\n');
		const int length = (end != nullptr) ? static_cast<int>(end - text) : static_cast<int>(strlen(text));
		PX4_INFO_RAW("%.*s\n", length, text);
		text += length + ((end != nullptr) ? 1 : 0);
	}
}

class ScopedLock
{
public:
	explicit ScopedLock(pthread_mutex_t &mutex) : _mutex(mutex) { pthread_mutex_lock(&_mutex); }
	~ScopedLock() { pthread_mutex_unlock(&_mutex); }
	ScopedLock(const ScopedLock &) = delete;
	ScopedLock &operator=(const ScopedLock &) = delete;

private:
	pthread_mutex_t &_mutex;
};

} // namespace

DspHitlModule::DspHitlModule()
{
	pthread_mutex_init(&_dsp_mutex, nullptr);
}

DspHitlModule::~DspHitlModule()
{
	pthread_mutex_destroy(&_dsp_mutex);
}

int DspHitlModule::task_spawn(int argc, char *argv[])
{
	_task_id = px4_task_spawn_cmd("dsp_hitl",
				      SCHED_DEFAULT,
				      SCHED_PRIORITY_FAST_DRIVER,
				      2048,
				      (px4_main_t)&run_trampoline,
				      (char *const *)argv);

	if (_task_id < 0) {
		_task_id = -1;
		return -errno;
	}

	return 0;
}

DspHitlModule *DspHitlModule::instantiate(int argc, char *argv[])
{
	DspHitlModule *instance = new DspHitlModule();

	if (instance == nullptr) {
		PX4_ERR("alloc failed");
	}

	return instance;
}

void DspHitlModule::run()
{
	const int imu_sub = orb_subscribe(ORB_ID(hil_sensor_imu));
	const int mag_baro_sub = orb_subscribe(ORB_ID(hil_sensor_mag_baro));

	if (imu_sub < 0 || mag_baro_sub < 0) {
		PX4_ERR("cannot subscribe to hil_sensor_imu / hil_sensor_mag_baro (%d)", errno);

		if (imu_sub >= 0) { orb_unsubscribe(imu_sub); }

		if (mag_baro_sub >= 0) { orb_unsubscribe(mag_baro_sub); }

		return;
	}

	px4_pollfd_struct_t fds[2] {};
	fds[0].fd = imu_sub;
	fds[0].events = POLLIN;
	fds[1].fd = mag_baro_sub;
	fds[1].events = POLLIN;

	{
		ScopedLock lock(_dsp_mutex);
		_dsp.start();
	}

	while (!should_exit()) {
		const int ready = px4_poll(fds, sizeof(fds) / sizeof(fds[0]), kPollTimeout_ms);

		if (ready < 0) {
			PX4_ERR("poll error %d", errno);
			px4_usleep(kPollTimeout_ms * 1000);
			continue;
		}

		if (ready == 0) {
			continue; // nothing new within 4 ms
		}

		const hrt_abstime now_us = hrt_absolute_time();

		if (fds[0].revents & POLLIN) {
			republish_imu(imu_sub, now_us);
		}

		if (fds[1].revents & POLLIN) {
			republish_mag_baro(mag_baro_sub, now_us);
		}
	}

	{
		ScopedLock lock(_dsp_mutex);
		_dsp.stop();
	}

	orb_unsubscribe(imu_sub);
	orb_unsubscribe(mag_baro_sub);
}

void DspHitlModule::republish_imu(int subscription, hrt_abstime now_us)
{
	hil_sensor_imu_s msg{};

	if (orb_copy(ORB_ID(hil_sensor_imu), subscription, &msg) != PX4_OK) {
		return;
	}

	std::optional<hitl::target::DspImuSamples> samples;
	{
		ScopedLock lock(_dsp_mutex);
		samples = _dsp.on_imu(hitl_px4::from_uorb(msg), now_us);
	}

	if (samples) {
		_sensor_accel_pub.publish(hitl_px4::to_uorb(samples->accel));
		_sensor_gyro_pub.publish(hitl_px4::to_uorb(samples->gyro));
	}
}

void DspHitlModule::republish_mag_baro(int subscription, hrt_abstime now_us)
{
	hil_sensor_mag_baro_s msg{};

	if (orb_copy(ORB_ID(hil_sensor_mag_baro), subscription, &msg) != PX4_OK) {
		return;
	}

	hitl::target::DspMagBaroSamples samples;
	{
		ScopedLock lock(_dsp_mutex);
		samples = _dsp.on_mag_baro(hitl_px4::from_uorb(msg), now_us);
	}

	if (samples.mag) {
		_sensor_mag_pub.publish(hitl_px4::to_uorb(*samples.mag));
	}

	if (samples.baro) {
		_sensor_baro_pub.publish(hitl_px4::to_uorb(*samples.baro));
	}
}

int DspHitlModule::print_status()
{
	char text[kStatusTextSize];
	{
		ScopedLock lock(_dsp_mutex);
		_dsp.format_status(text, sizeof(text));
	}
	print_lines(text);
	return 0;
}

int DspHitlModule::print_stopped_status()
{
	char text[kStatusTextSize];
	hitl::target::format_dsp_hitl_status(text, sizeof(text), false, hitl::target::DspHitlCounters{},
					     hitl::target::DspHitlCurrent{});
	print_lines(text);
	return 1; // as ModuleBase's status of a module that is not running
}

int DspHitlModule::custom_command(int argc, char *argv[])
{
	print_usage("unknown command");
	return 1;
}

int DspHitlModule::print_usage(const char *reason)
{
	if (reason) {
		PX4_WARN("%s\n", reason);
	}

	// One short line: PX4's posix console cuts a print at 127 characters.
	PRINT_MODULE_DESCRIPTION("HITL sensor shim (hitl target/px4): hil_sensor_imu, hil_sensor_mag_baro -> sensor_accel/gyro/mag/baro");

	PRINT_MODULE_USAGE_NAME("dsp_hitl", "driver");
	PRINT_MODULE_USAGE_COMMAND("start");
	PRINT_MODULE_USAGE_DEFAULT_COMMANDS();

	return 0;
}

extern "C" __EXPORT int dsp_hitl_main(int argc, char *argv[])
{
	if (argc >= 2 && strcmp(argv[1], "status") == 0 && !DspHitlModule::is_running()) {
		return DspHitlModule::print_stopped_status();
	}

	return DspHitlModule::main(argc, argv);
}
