// The dashboard's three client links to the autopilot through a client port (a session's or a
// bridge's, 127.0.0.1:14600), each on its own thread: the telemetry feed (vehicle, EKF,
// STATUSTEXT), the shell poller (`qshell dsp_hitl status` once a second, and the `s` key's one
// command) and the command worker (a arm, d disarm, t takeoff, l land). The same code path as
// `hitl arm` from another terminal. Shared by every dashboard that reaches a board.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "engine/model/vehicle_config.h"
#include "engine/telemetry/dsp_hitl_meter.h"
#include "engine/vehicle/command_worker.h"
#include "engine/vehicle/shell_poller.h"
#include "engine/vehicle/telemetry_feed.h"
#include "tui/actions.h"
#include "tui/dashboard_model.h"
#include "tui/message_log.h"

namespace hitl::tui {

/// The board's dsp_hitl counters at real time: the spec's split (hil_sensor_imu 250 Hz,
/// hil_sensor_mag_baro 100 Hz) and the simulated magnetometer's and barometer's rates.
telemetry::DspHitlExpectedRates dsp_hitl_rates(const model::SensorsConfig& sensors);

class BoardClients {
 public:
  /// `clients_port` 0: no links; every board panel then says so and the acting keys are refused.
  /// `truth_sysid`: the simulator whose ODOMETRY is ground truth (none outside a simulation).
  /// Outcomes, STATUSTEXT and shell output go to `log`, which must outlive this.
  BoardClients(uint16_t clients_port, std::optional<uint8_t> truth_sysid, const telemetry::DspHitlExpectedRates& rates,
               MessageLog& log);
  ~BoardClients();  ///< stops and joins the three threads
  BoardClients(const BoardClients&) = delete;
  BoardClients& operator=(const BoardClients&) = delete;

  void stop();
  /// Why nothing can be sent to the autopilot now, or nullopt when it can.
  std::optional<std::string> link_refusal() const;
  /// For the keys these links carry (Arm, Disarm, ForceDisarm, Takeoff, Land, Shell).
  std::optional<std::string> refusal(Action action) const;
  /// Starts one of those keys' actions; returns at once.
  void perform(Action action, const std::string& argument);
  /// The EKF, vehicle and dsp_hitl panels and the footer's busy note; `pace` (the real-time
  /// factor) scales the dsp_hitl counters' expected rates.
  void fill(DashboardModel& model, double pace) const;

 private:
  uint16_t clients_port_;
  MessageLog& log_;
  std::unique_ptr<vehicle::TelemetryFeed> feed_;
  std::unique_ptr<vehicle::ShellPoller> shell_;
  std::unique_ptr<vehicle::CommandWorker> commands_;
};

}  // namespace hitl::tui
