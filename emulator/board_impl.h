// Inside Board (board.h), shared by the files that each own one side of it:
//   board.cpp           wiring: the instances, the VIO listener, the loop, snapshots
//   board_hil.cpp       the HIL input side: HIL_SENSOR / HIL_GPS into the split, dsp_hitl, the flight core
//   board_streams.cpp   the telemetry side: streams, HEARTBEAT, HIL_ACTUATOR_CONTROLS, STATUSTEXT
//   board_commands.cpp  commands, the parameter protocol, TIMESYNC, sticks
//   board_shell.cpp     the board's shell (SERIAL_CONTROL), voxl-hitl-vio-server --status
// Not a public header: `hitl target` and `hitl demo` use board.h.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "emulator/board.h"
#include "emulator/flight_adapter.h"
#include "emulator/hil_input.h"
#include "emulator/mavlink_instance.h"
#include "emulator/param_store.h"
#include "emulator/shell.h"
#include "engine/mavlink/statustext.h"
#include "engine/net/busy_poll.h"
#include "engine/net/udp_endpoint.h"
#include "target/core/dsp_hitl.h"
#include "target/core/hil_split.h"

namespace hitl::target {

struct Board::Impl {
  BoardConfig config;
  mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  std::unique_ptr<MavlinkInstance> hil;
  std::unique_ptr<MavlinkInstance> gcs;
  std::optional<net::UdpEndpoint> vio;
  std::optional<mavlink::FrameParser> vio_parser;
  ParamStore params;
  std::unique_ptr<FlightAdapter> flight;
  HilSplit split;
  DspHitl dsp;
  std::optional<Shell> shell;
  LockstepClock lockstep_clock;
  net::AdaptiveBusyPoll busy_poll;  ///< lockstep: a moment's polling for the next HIL_SENSOR before sleeping
  /// Lockstep: a HIL_SENSOR was taken and its HIL_ACTUATOR_CONTROLS is owed. It is sent last in the
  /// loop's pass, after everything the same input caused (command acks, the streams due at the new
  /// time), so the simulator, which steps on at the answer, has read all of it by then: the same
  /// input gives the same answers in the same steps (docs/replay.md "Deterministic").
  std::vector<mavlink::msg::HilActuatorControls> answers_owed;  ///< at most kMaxAnswersOwed
  static constexpr std::size_t kMaxAnswersOwed = 64;

  uint64_t start_us = 0;
  uint64_t now_us = 0;  ///< board time since start
  uint64_t hil_sensor_received = 0, hil_gps_received = 0, odometry_received = 0, actuators_sent = 0;
  uint64_t commands_received = 0, params_set = 0;
  std::array<double, 4> motors{};
  double vio_rate_hz = 0, vio_rate_since_s = 0;
  uint64_t vio_rate_count = 0;

  mutable std::mutex snapshot_mutex;
  BoardSnapshot published;

  // --- wiring (board.cpp) ----------------------------------------------------------------------
  std::vector<MavlinkInstance*> instances();
  /// SYS_HITL is 1.
  bool hil_mode() const;
  uint32_t boot_ms() const { return static_cast<uint32_t>(now_us / 1000); }
  /// The board runs on its own (wall) clock: always outside lockstep, in lockstep until the first HIL_SENSOR.
  bool on_wall_clock() const { return !config.lockstep || !lockstep_clock.started(); }
  /// One frame from an instance, to the side that handles its id.
  void handle_frame(const mavlink::Frame& f, MavlinkInstance& inst);
  void drain_vio();
  /// voxl-hitl-vio-server's ODOMETRY rate (wall clock, as the real server measures it), per status.
  void measure_vio_rate();
  BoardSnapshot make_snapshot() const;
  void publish();

  // --- the HIL input side (board_hil.cpp) -------------------------------------------------------
  void on_hil_sensor(const mavlink::msg::HilSensor& m);
  void on_hil_gps(const mavlink::msg::HilGps& m);
  /// The split's due publications through dsp_hitl into the flight core, which steps the motors.
  void process_board(uint64_t t_us);

  // --- the telemetry side (board_streams.cpp) ---------------------------------------------------
  /// HEARTBEAT.base_mode: the flight stack's flags, plus HIL when SYS_HITL is 1 (as commander does).
  uint8_t base_mode_with_hil(const FlightState& s) const;
  /// To every instance; a text over 50 characters in chunks, as PX4 sends it.
  void statustext(const std::string& text, mavlink::MavSeverity severity);
  mavlink::StatusTextChunker statustext_chunker;
  /// The flight stack's messages (flight->take_messages()) as STATUSTEXT, each with its severity.
  void say_flight_messages();
  void send_stream(MavlinkInstance& inst, uint32_t id);
  void send_actuators(MavlinkInstance& inst);
  /// The HIL_ACTUATOR_CONTROLS the board would send now (stamped, flagged, armed or not).
  mavlink::msg::HilActuatorControls actuator_message() const;
  /// Lockstep: sends the answers owed, in order.
  void send_owed_answers();
  /// The start script's stream configuration (spec step 9) and PX4's defaults for the rest.
  void default_streams(MavlinkInstance& inst, bool is_hil);

  // --- commands and parameters (board_commands.cpp) ---------------------------------------------
  void ack(MavlinkInstance& inst, uint16_t command, mavlink::MavResult result, const mavlink::Frame& from);
  void handle_command(MavlinkInstance& inst, const mavlink::Frame& f, uint16_t command, const std::array<float, 7>& p);
  void send_param(MavlinkInstance& inst, std::size_t index);
  void on_param_request_read(MavlinkInstance& inst, const mavlink::msg::ParamRequestRead& m);
  void on_param_set(MavlinkInstance& inst, const mavlink::msg::ParamSet& m);
  void on_timesync(MavlinkInstance& inst, const mavlink::Frame& f);
  void on_manual_control(const mavlink::msg::ManualControl& m);

  // --- the shell (board_shell.cpp) --------------------------------------------------------------
  ShellResult shell_command(const std::string& line);
  /// The apps processor's `voxl-hitl-vio-server --status [--json]` (target/vio-server), which the
  /// emulated board answers in its one shell: its VIO listener is that server.
  std::string vio_server_status(bool json) const;
};

}  // namespace hitl::target
