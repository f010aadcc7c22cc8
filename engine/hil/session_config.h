// Everything a HITL session needs to know, filled by defaults < config file < flags in cli/.
// Defaults are the spec's ports and rates (DESIGN.md §4).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/mavlink/frame.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/world_config.h"
#include "engine/vehicle/trajectory.h"
#include "engine/vehicle/trajectory_pilot.h"
#include "target/core/board_ports.h"

namespace hitl::hil {

using ::hitl::kBoardHilPort;       // the port table: target/core/board_ports.h
using ::hitl::kBoardVioPort;
using ::hitl::kSessionClientPort;
using ::hitl::kSimLocalPort;
inline constexpr uint16_t kPx4SitlTcpPort = 4560;    ///< PX4 SITL's simulator_mavlink (instance 0)
inline constexpr double kStepPeriod_s = 0.004;       ///< physics step and HIL_SENSOR period
inline constexpr double kVioRate_hz = 250.0;
/// Lockstep: a flight stack that answered once and then stays silent this long (wall time, pauses
/// excluded) is gone; the session ends (exit 1) instead of stepping on without it.
inline constexpr double kLockstepGiveUp_s = 10.0;
inline constexpr uint8_t kSimulatorSystemId = 250;   ///< the simulator's own identity (not a vehicle)
inline constexpr uint8_t kSimulatorComponentId = 1;
/// ODOMETRY comes from its own component (MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY), with its own
/// sequence, so a recording of both links shows no false loss.
inline constexpr uint8_t kVioComponentId = 197;
/// Ground truth for clients (trajectory tracking error, the dashboard): ODOMETRY in local NED from
/// the simulator's own system id, estimator type MOCAP (external ground truth).
inline constexpr double kTruthToClientsRate_hz = 50.0;
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

/// Who is on the other end of the HIL link.
enum class FlightStackLink {
  BoardUdp,  ///< a VOXL2 / PX4 in HIL mode: UDP to target:hil_port from local_port
  SitlTcp,   ///< PX4 SITL's simulator_mavlink: hitl listens on TCP, PX4 connects, lockstep on PX4's clock
  SitlUdp    ///< the same over UDP (simulator_mavlink built for UDP)
};

struct SessionConfig {
  FlightStackLink link = FlightStackLink::BoardUdp;
  std::string target_ip = "127.0.0.1";   ///< -i / --target-ip / --mavlink-addr
  uint16_t hil_port = kBoardHilPort;      ///< --hil-port / --mavlink-udp-remote-port
  uint16_t local_port = kSimLocalPort;    ///< --local-port / --mavlink-udp-local-port
  std::string bind_address = "0.0.0.0";
  uint16_t sitl_port = kPx4SitlTcpPort;   ///< --px4-sitl tcp:PORT / udp:PORT

  bool vio = true;                        ///< --no-vio / --en-vio-output
  std::string vio_ip;                     ///< --vio-ip (empty: the target IP)
  uint16_t vio_port = kBoardVioPort;      ///< --vio-port / --vio-udp-remote-port
  double vio_rate_hz = kVioRate_hz;       ///< --vio-rate / --vio-update-rate

  uint8_t sysid = kSimulatorSystemId;     ///< --sysid: the simulator's HEARTBEAT and frames
  uint8_t compid = kSimulatorComponentId;
  mavlink::Version protocol = mavlink::Version::V2;  ///< --protocol-version 1.0|2.0

  double speed = 1.0;                     ///< --speed: real-time factor; 0 = as fast as possible
  double duration_s = 0;                  ///< --duration: simulated seconds, 0 = until stopped
  bool lockstep = false;                  ///< --lockstep / --enable-lockstep
  double lockstep_timeout_s = 0.5;        ///< --lockstep-timeout
  bool realtime = false;                  ///< --realtime: SCHED_FIFO + mlockall when permitted
  double actuator_timeout_s = 0.5;        ///< --actuator-timeout
  double no_answer_warning_s = 2.0;       ///< say so when nothing came back this long after the first HIL_SENSOR

  model::VehicleConfig vehicle;           ///< --vehicle FILE over the compiled-in x500
  model::WorldConfig world;               ///< --world FILE
  uint64_t seed = 1;                      ///< --seed
  bool noise = true;                      ///< --no-noise
  std::string record_path;                ///< --record FILE.tlog: everything sent and received

  std::optional<vehicle::Trajectory> trajectory;  ///< -t FILE: fly it (trajectory_rc), then end the session
  vehicle::StickMode trajectory_mode = vehicle::StickMode::Velocity;  ///< --trajectory-mode

  uint16_t clients_port = kSessionClientPort;  ///< --clients (0: none)
  std::string clients_bind = "127.0.0.1";
  std::string gcs;                        ///< --gcs HOST:PORT (empty: none)
  double truth_rate_hz = kTruthToClientsRate_hz;  ///< --truth-rate: truth ODOMETRY to clients (0: none)
};

}  // namespace hitl::hil
