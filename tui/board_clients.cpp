#include "tui/board_clients.h"

#include <thread>

#include "engine/vehicle/patient_link.h"
#include "tui/collect.h"

namespace hitl::tui {
namespace {

vehicle::OperatorCommand command_for(Action a) {
  switch (a) {
    case Action::Disarm: return vehicle::OperatorCommand::Disarm;
    case Action::ForceDisarm: return vehicle::OperatorCommand::ForceDisarm;
    case Action::Takeoff: return vehicle::OperatorCommand::Takeoff;
    case Action::Land: return vehicle::OperatorCommand::Land;
    default: return vehicle::OperatorCommand::Arm;
  }
}

bool is_command(Action a) {
  return a == Action::Arm || a == Action::Disarm || a == Action::ForceDisarm || a == Action::Takeoff || a == Action::Land;
}

}  // namespace

telemetry::DspHitlExpectedRates dsp_hitl_rates(const model::SensorsConfig& sensors) {
  return telemetry::dsp_hitl_expected_rates(sensors.mag.rate_hz, sensors.baro.rate_hz);
}

BoardClients::BoardClients(uint16_t clients_port, std::optional<uint8_t> truth_sysid,
                           const telemetry::DspHitlExpectedRates& rates, MessageLog& log)
    : clients_port_(clients_port), log_(log) {
  if (clients_port_ == 0) {
    log_.add(Severity::Warning, "--clients 0: no client port, so the dashboard cannot reach the board (vehicle, EKF, "
                                "dsp_hitl and the keys that act are off)");
    return;
  }
  const auto link = vehicle::session_client_options(clients_port_);
  feed_ = std::make_unique<vehicle::TelemetryFeed>(
      link, vehicle::dashboard_streams(),
      [this](mavlink::MavSeverity s, const std::string& text) { log_.add_statustext(severity_from_mavlink(static_cast<uint8_t>(s)), "autopilot", text); },
      truth_sysid);
  shell_ = std::make_unique<vehicle::ShellPoller>(link, rates, 1.0, [this](const std::string& command, bool ok, const std::string& output) {
    log_.add(Severity::Notice, "shell> " + command);
    if (ok) log_.add_lines(Severity::Info, output);
    else log_.add(Severity::Error, output);
    log_.add_outcome(ok ? Severity::Notice : Severity::Error,
                     "shell> " + command + (ok ? ": done, its output in Messages" : ": " + output));
  });
  commands_ = std::make_unique<vehicle::CommandWorker>(
      link, [this](vehicle::OperatorCommand, bool ok, const std::string& text) { log_.add_outcome(ok ? Severity::Notice : Severity::Error, text); });
}

BoardClients::~BoardClients() { stop(); }

void BoardClients::stop() {
  // All three at once: each may be in the middle of a wait (up to 0.2 s), and quitting should not
  // take the sum of them.
  std::thread commands([this] {
    if (commands_) commands_->stop();
  });
  std::thread shell([this] {
    if (shell_) shell_->stop();
  });
  if (feed_) feed_->stop();
  commands.join();
  shell.join();
}

std::optional<std::string> BoardClients::link_refusal() const {
  if (!feed_) return "no client port (--clients 0): the dashboard cannot reach the board";
  const auto f = feed_->snapshot();
  if (!f.connected) return "no autopilot yet (" + f.link + ")";
  return std::nullopt;
}

std::optional<std::string> BoardClients::refusal(Action action) const {
  if (auto why = link_refusal()) return why;
  if (is_command(action) && commands_->pending() >= 3) return "three commands are already waiting for their ACK";
  return std::nullopt;
}

void BoardClients::perform(Action action, const std::string& argument) {
  if (auto why = refusal(action)) {  // it changed since the key asked
    log_.add_outcome(Severity::Warning, std::string(to_string(action)) + ": " + *why);
    return;
  }
  if (action == Action::Shell) {
    shell_->run_command(argument);
  } else if (is_command(action)) {
    log_.add_outcome(Severity::Info, std::string(to_string(action)) + " ...");
    commands_->submit(command_for(action));
  }
}

void BoardClients::fill(DashboardModel& m, double pace) const {
  if (!feed_) {
    const std::string why = "no client port (--clients 0)";
    m.ekf = EkfPanel{};
    m.ekf->unavailable = why;
    m.vehicle = VehiclePanel{};
    m.vehicle->unavailable = why;
    m.dsp_hitl = DspHitlPanel{};
    m.dsp_hitl->unavailable = why;
    return;
  }
  const auto f = feed_->snapshot();
  m.ekf = ekf_from(f);
  m.vehicle = vehicle_from(f);
  m.dsp_hitl = dsp_hitl_from(shell_->dsp_hitl(), pace);
  if (commands_->pending() > 0) m.busy = "command in flight";
}

}  // namespace hitl::tui
