// Faults `hitl target --fault NAME` injects, one per thing `hitl doctor` looks for (docs/doctor.md),
// so that each of doctor's checks can be shown to fail when it should. Each is a deliberate
// misbehaviour of the emulated board, at one clearly named place:
//
//   no-actuators        board_streams.cpp, send_actuators: no HIL_ACTUATOR_CONTROLS at all (the stream not
//                       configured by the start script)
//   wrong-flags         board_streams.cpp, send_actuators: flags 0 instead of the VOXL2's 0x0F (a PX4 build
//                       without the VOXL2 HIL change)
//   wrong-cal-acc0-id   Board::create: CAL_ACC0_ID = kWrongAccelDeviceId, not dsp_hitl's accel ID;
//                       the accelerometer is then uncalibrated and arming is refused
//   sys-hitl-0          Board::create: SYS_HITL 0; HEARTBEAT lacks MAV_MODE_FLAG_HIL_ENABLED
//   dsp-hitl-stalled    board_hil.cpp, process_board: after kDspStallAfterImu hil_sensor_imu MUORB stops
//                       delivering hil_sensor_* to the DSP: dsp_hitl's counters freeze (it still says
//                       "Running: yes"), PX4 gets no more IMU, mag or baro
//   ekf-not-converging  flight_adapter.cpp, on_mag: each magnetometer sample turned kEkfFaultMagSwing_rad
//                       about body down, alternately right and left (magnetic interference), so every
//                       sample disagrees with the heading by ~90 deg: the heading test ratio stays
//                       about 3 (above 1: rejected) and the estimator never converges in yaw
//                       (a gated measurement, GPS or baro, would be re-admitted once the estimator's
//                       variance grew; the heading is not, so the fault holds for good)
//   no-vio-listener     Board::create: no socket on --vio-port (voxl-hitl-vio-server not running)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::target {

enum class Fault { NoActuators, WrongFlags, WrongCalAcc0Id, SysHitl0, DspHitlStalled, EkfNotConverging, NoVioListener };

/// The injected set; all false is a healthy board.
struct BoardFaults {
  bool no_actuators = false;
  bool wrong_flags = false;
  bool wrong_cal_acc0_id = false;
  bool sys_hitl_0 = false;
  bool dsp_hitl_stalled = false;
  bool ekf_not_converging = false;
  bool no_vio_listener = false;

  void set(Fault fault);
  bool any() const;
  /// "wrong-flags, sys-hitl-0" (empty when none).
  std::string names() const;
};

/// HIL_ACTUATOR_CONTROLS.flags under wrong-flags: upstream PX4's value, without the VOXL2 bitmask.
inline constexpr uint64_t kWrongActuatorFlags = 0x00;
/// CAL_ACC0_ID under wrong-cal-acc0-id: dsp_hitl's accel ID on another address (0x02), as a
/// calibration made against another sensor leaves it.
inline constexpr int32_t kWrongAccelDeviceId = 1311244;
/// dsp-hitl-stalled: hil_sensor_imu delivered before MUORB stops (2 s at 250 Hz: the counters are
/// non-zero, then frozen, as the spec's troubleshooting describes).
inline constexpr uint64_t kDspStallAfterImu = 500;
/// ekf-not-converging: how far each magnetometer sample is turned, alternately right and left (90 deg).
inline constexpr double kEkfFaultMagSwing_rad = 1.5707963267948966;

/// Every fault name, in the order above ("no-actuators", ...).
const std::vector<std::string>& fault_names();
/// A name of fault_names(); an Error naming the input and the valid names otherwise.
Expected<Fault> parse_fault(const std::string& name);
const char* to_string(Fault fault);

}  // namespace hitl::target
