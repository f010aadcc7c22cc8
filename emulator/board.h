// `hitl target`: an emulated VOXL2 / M0197 board, so everything can be flown and tested without
// hardware. It is NOT PX4: it speaks PX4's dialect (autopilot type, custom modes, parameters,
// shell) over the board's MAVLink instances, runs the spec's HIL split and dsp_hitl republish
// (target/core), estimates from the sensors only and flies the x500 with a PX4-structured cascade
// (emulator/flight). Never prints: events and snapshots go to an observer.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "emulator/faults.h"

namespace hitl::target {

using ::hitl::kBoardGcsPort;  // the port table: base/contract/board_ports.h

struct BoardConfig {
  std::string bind_address = "0.0.0.0";  ///< --bind
  uint16_t hil_port = kBoardHilPort;      ///< --hil-port: the primary (HIL) instance
  uint16_t gcs_port = kBoardGcsPort;      ///< --gcs-port: the GCS instance (0: none)
  uint16_t vio_port = kBoardVioPort;      ///< --vio-port: voxl-hitl-vio-server's listener (0: none)
  /// Each listener that is on (its port not 0) binds a port the OS picks instead (Board::ports()
  /// says which): a campaign's parallel boards, each keeping its sockets from the start.
  bool os_picks_ports = false;
  bool lockstep = false;   ///< --lockstep: the board's clock is HIL_SENSOR.time_usec and each HIL_SENSOR gets one answer
  double duration_s = 0;   ///< --duration: stop after this much board time (0: until stopped)
  uint8_t sysid = 1;
  uint8_t compid = 1;      ///< MAV_COMP_ID_AUTOPILOT1
  uint64_t actuator_interval_us = kActuatorStreamPeriod_us;  ///< HIL_ACTUATOR_CONTROLS at 200 Hz (real-time clock)
  BoardFaults faults;      ///< --fault NAME (repeatable): what hitl doctor must catch (faults.h)
};

struct BoardEvent {
  Severity severity = Severity::Info;
  std::string text;
};

/// What `--json` and the summary report.
struct BoardSnapshot {
  double board_time_s = 0;
  bool armed = false;
  std::string mode;
  std::string landed_state;
  bool estimator_ready = false;
  std::string not_ready_reason;
  double altitude_m = 0;  ///< estimate, above home
  uint64_t hil_sensor_received = 0;
  uint64_t hil_gps_received = 0;
  uint64_t odometry_received = 0;
  uint64_t actuators_sent = 0;
  uint64_t commands_received = 0;
  uint64_t params_set = 0;
  uint64_t shell_commands = 0;
  uint64_t malformed = 0;  ///< CRC, parse and truncation errors on all links
  std::string hil_partner;
  std::string gcs_partner;
  std::string dsp_hitl_status;
};

/// The ports the board's sockets are bound to (a port 0 in BoardConfig: the one the OS gave).
struct BoardPorts {
  uint16_t hil_port = 0;
  uint16_t gcs_port = 0;  ///< 0: no GCS instance
  uint16_t vio_port = 0;  ///< 0: no VIO listener
};

class Board {
 public:
  class Observer {
   public:
    virtual ~Observer() = default;
    virtual void on_event(const BoardEvent& /*event*/) {}
    virtual void on_status(const BoardSnapshot& /*snapshot*/) {}  ///< once a second
  };
  enum class EndReason { Duration, Stopped };

  static Expected<std::unique_ptr<Board>> create(const BoardConfig& config);
  ~Board();
  Expected<EndReason> run(const std::atomic<bool>& stop, Observer& observer);
  BoardSnapshot snapshot() const;
  std::string describe() const;
  /// Where the board listens: with port 0 in the config, the ports the OS picked (the board keeps
  /// the sockets, so nothing else can take them: no bind-then-close probing).
  BoardPorts ports() const;

 private:
  struct Impl;
  explicit Board(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hitl::target
