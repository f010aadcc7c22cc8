// Everything a HITL session needs to know, filled by defaults < config file < flags in cli/.
// Defaults are the spec's ports and rates (DESIGN.md §4).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/frame.h"
#include "engine/faults/fault_spec.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/world_config.h"
#include "engine/net/link_spec.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_process.h"
#include "engine/sensors/unit_set.h"
#include "engine/vehicle/trajectory.h"
#include "engine/vehicle/trajectory_pilot.h"

namespace hitl::hil {

using ::hitl::kBoardHilPort;       // the port table: base/contract/board_ports.h
using ::hitl::kBoardVioPort;
using ::hitl::kSessionClientPort;
using ::hitl::kSimLocalPort;
inline constexpr uint16_t kPx4SitlTcpPort = 4560;    ///< PX4 SITL's simulator_mavlink (instance 0)
using ::hitl::kStepPeriod_s;       // the rates: base/contract/data_rates.h
using ::hitl::kVioRate_hz;
/// Lockstep: a flight stack that answered once and then stays silent this long (wall time, pauses
/// excluded) is gone; the session ends (exit 1) instead of stepping on without it.
inline constexpr double kLockstepGiveUp_s = 10.0;
/// Ground truth for clients (trajectory tracking error, the dashboard): ODOMETRY in local NED from
/// the simulator's own system id, estimator type MOCAP (external ground truth).
inline constexpr double kTruthToClientsRate_hz = 50.0;
using ::hitl::kSimulatorComponentId;  // the session's identity and status: base/contract/session_status.h
using ::hitl::kSimulatorSystemId;
using ::hitl::kVioComponentId;

/// hitl sim --px4: a PX4 SITL build that the session starts, owns and stops (engine/hil/px4_launch.h).
struct Px4Options {
  px4::Px4Build build;                ///< --px4 DIR, found (px4::find_px4_build: a build folder or a PX4 tree)
  std::vector<px4::Px4Param> params;  ///< --px4-param NAME=VALUE, over the vehicle's (hil/px4_vehicle_params.h)
  double connect_timeout_s = 30;      ///< --px4-timeout: PX4 must connect to the simulator port within this
  /// PX4's working folder (its parameters, logs and ULogs stay there); empty: beside the recording
  /// (FILE.px4/) or a new $TMPDIR/hitl-px4-XXXXXX
  std::string work_dir;
};

struct SessionConfig {
  /// --px4: PX4 SITL that the session starts (its simulator link is then the instance's TCP port)
  std::optional<Px4Options> px4;
  /// --px4-sitl: PX4 SITL's simulator link instead of a board (stack_peer.h decides what follows)
  std::optional<net::LinkSpec> px4_sitl;
  std::string target_ip = "127.0.0.1";   ///< -i / --target-ip / --mavlink-addr
  uint16_t hil_port = kBoardHilPort;      ///< --hil-port / --mavlink-udp-remote-port
  uint16_t local_port = kSimLocalPort;    ///< --local-port / --mavlink-udp-local-port
  std::string bind_address = "0.0.0.0";

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
  double spin_us = 0;                     ///< --spin-us: the last part of each tick's wait spent spinning (0..2000)
  double actuator_timeout_s = 0.5;        ///< --actuator-timeout
  double no_answer_warning_s = 2.0;       ///< say so when nothing came back this long after the first HIL_SENSOR

  model::VehicleConfig vehicle;           ///< --vehicle FILE over the compiled-in x500
  std::string imu_profile;                ///< the vehicle file's sensors.imu.profile, said with the IMU's noise at the start ("" : not said)
  sensors::UnitConfigs sensor_units;      ///< the sensor units (--vehicle FILE's sensors.<name>, --<name>): off by default
  model::WorldConfig world;               ///< --world FILE
  uint64_t seed = 1;                      ///< --seed
  /// --board-timing: the board's data path delays on the sensors (sensors/data_path_timing.h);
  /// "none" sends each sample as it is taken.
  std::string board_timing = "none";
  bool noise = true;                      ///< --no-noise
  std::string record_path;                ///< --record FILE.tlog: everything sent and received

  std::optional<vehicle::Trajectory> trajectory;  ///< -t FILE: fly it (trajectory_rc), then end the session
  vehicle::StickMode trajectory_mode = vehicle::StickMode::Velocity;  ///< --trajectory-mode

  uint16_t clients_port = kSessionClientPort;  ///< --clients (0: none)
  std::string clients_bind = "127.0.0.1";
  std::string gcs;                        ///< --gcs udp:HOST:PORT or HOST:PORT (empty: none)
  double truth_rate_hz = kTruthToClientsRate_hz;  ///< --truth-rate: truth ODOMETRY to clients (0: none)

  std::vector<faults::FaultSpec> faults;  ///< --fault and --scenario (docs/faults.md)
};

}  // namespace hitl::hil
