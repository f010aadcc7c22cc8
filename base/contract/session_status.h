// What a running session says about itself to its clients, the names and identities `hitl doctor`,
// the dashboards and other hitl commands read (docs/sim.md, docs/doctor.md).
#pragma once

#include <cstdint>
#include <string_view>

namespace hitl {

inline constexpr uint8_t kSimulatorSystemId = 250;   ///< the simulator's own identity (not a vehicle)
inline constexpr uint8_t kSimulatorComponentId = 1;
/// ODOMETRY comes from its own component (MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY), with its own
/// sequence, so a recording of both links shows no false loss.
inline constexpr uint8_t kVioComponentId = 197;
/// The session's own state, to clients once a second (NAMED_VALUE_FLOAT / _INT from sysid 250),
/// beside a HEARTBEAT whose system_status is STANDBY while paused.
inline constexpr std::string_view kStatusRtfName = "sim_rtf";     ///< recent real-time factor
inline constexpr std::string_view kStatusLateName = "sim_late";   ///< late ticks so far
inline constexpr std::string_view kStatusPauseName = "sim_pause"; ///< 1 while paused
/// For `hitl doctor` (docs/doctor.md), in the same message each second (NAMED_VALUE names hold at
/// most 10 characters):
inline constexpr std::string_view kStatusSpeedName = "sim_speed";     ///< FLOAT: the requested --speed (0: as fast as possible)
inline constexpr std::string_view kStatusLockstepName = "sim_lockst"; ///< INT: 1 in lockstep (with the board or PX4 SITL)
inline constexpr std::string_view kStatusActuatorRateName = "sim_act_hz";  ///< FLOAT: HIL_ACTUATOR_CONTROLS received, Hz of wall time, last window
inline constexpr std::string_view kStatusActuatorFlagsName = "sim_act_fl"; ///< INT: the last one's flags (-1: none yet)
inline constexpr std::string_view kStatusActuatorArmedName = "sim_act_ar"; ///< INT: the last one's MAV_MODE_FLAG_SAFETY_ARMED (0/1; -1: none yet)
inline constexpr std::string_view kStatusLoopLatencyP99Name = "sim_lat99";  ///< INT: loop latency's p99 so far, us (-1: none answered yet)
/// INT, only from a session that started PX4 SITL (hitl sim --px4): its instance N (TCP 4560+N, GCS
/// UDP 18570+N, system id N+1) once PX4 has connected to the simulator port, -1 while waiting.
inline constexpr std::string_view kStatusPx4InstanceName = "sim_px4";
/// For `hitl report`'s loop-latency plot (docs/report.md), beside sim_lat99 and alike:
inline constexpr std::string_view kStatusLoopLatencyP50Name = "sim_lat50";  ///< INT: loop latency's median so far, us (-1: none yet)
inline constexpr std::string_view kStatusLoopLatencyMaxName = "sim_latmx";  ///< INT: loop latency's max so far, us (-1: none yet)

/// NAMED_VALUE_FLOAT in a recording (hitl sim -t --record, engine/hil/flight_record.h): the trajectory
/// pilot's position error at each scored step, metres; the session's tracking RMS/max are of these.
inline constexpr std::string_view kTrackingErrorName = "trk_err";

}  // namespace hitl
