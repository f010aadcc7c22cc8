#include "tui/sim_dashboard.h"

#include <cmath>
#include <limits>
#include <numeric>

#include "base/common/clock.h"
#include "base/contract/data_rates.h"
#include "engine/faults/fault_spec.h"
#include "engine/vehicle/patient_link.h"
#include "tui/collect.h"
#include "tui/draw.h"

namespace hitl::tui {

SimDashboard::SimDashboard(hil::Session& session, const hil::SessionConfig& config, SimDashboardConfig dashboard)
    : session_(session),
      config_(config),
      dashboard_(std::move(dashboard)),
      board_(config_.clients_port, config_.sysid, dsp_hitl_rates(config_.vehicle.sensors), log_) {
  // One clock on the screen: the header's simulated time stamps the messages too (and the reset's).
  log_.set_clock([this] { return session_.snapshot().sim_time_s; });
  log_.add(Severity::Info, dashboard_.title + ": " + session_.describe() + "; ? for the keys");
}

SimDashboard::~SimDashboard() { shutdown(); }

void SimDashboard::shutdown() {
  trajectory_.stop();
  board_.stop();
}

void SimDashboard::on_event(const hil::SessionEvent& event) {
  const Severity s = event.severity;
  // Pause, resume and reset come from the keys: their outcome is pinned in the header.
  const bool key_outcome = event.text.rfind("paused at", 0) == 0 || event.text.rfind("resumed at", 0) == 0 ||
                           event.text.rfind("reset to home", 0) == 0;
  if (key_outcome) log_.add_outcome(s, event.text);
  else log_.add(s, event.text);
}

void SimDashboard::mark_finished(const std::string& why) {
  std::lock_guard<std::mutex> lock(finished_mutex_);
  finished_ = why;
}

std::optional<std::string> SimDashboard::finished() {
  std::lock_guard<std::mutex> lock(finished_mutex_);
  return finished_;
}

std::optional<std::string> SimDashboard::refusal(Action action) const {
  switch (action) {
    case Action::TogglePause:
    case Action::ResetHome:
    case Action::Fault: return std::nullopt;
    case Action::StopTrajectory:
      if (!trajectory_.running()) return "no trajectory is being flown";
      return std::nullopt;
    case Action::FlyTrajectory:
      if (!dashboard_.trajectory) return "no trajectory file: " + dashboard_.no_trajectory_hint;
      if (trajectory_.running()) return "a trajectory is already being flown";
      return board_.link_refusal();
    case Action::Arm:
    case Action::Disarm:
    case Action::ForceDisarm:
    case Action::Takeoff:
    case Action::Land:
    case Action::Shell: return board_.refusal(action);
  }
  return std::nullopt;
}

void SimDashboard::perform(Action action, const std::string& argument) {
  switch (action) {
    case Action::TogglePause: session_.set_paused(!session_.snapshot().paused); return;
    case Action::ResetHome: session_.request_reset(); return;
    case Action::Fault: {
      if (argument.rfind("clear", 0) == 0) {
        const auto name = argument.find_first_not_of(' ', 5);
        session_.clear_faults(name == std::string::npos ? "" : argument.substr(name));
        return;
      }
      auto spec = faults::parse_live_fault(argument);
      if (!spec) log_.add(Severity::Warning, "fault: " + spec.error().message);
      else session_.start_fault(*spec);
      return;
    }
    case Action::StopTrajectory:
      log_.add_outcome(Severity::Notice, "stopping the trajectory");
      trajectory_.stop();
      return;
    case Action::FlyTrajectory: {
      const std::string port = std::to_string(config_.clients_port);
      // Through the session's client port, as `hitl fly trajectory` from another terminal flies it.
      log_.add_outcome(Severity::Notice, "f: flying " + dashboard_.trajectory_file + " through 127.0.0.1:" + port);
      vehicle::FlyTrajectoryOptions options;
      options.mode = dashboard_.trajectory_mode;
      options.truth_sysid = config_.sysid;
      options.on_tracking_error = [this](double e) { tracking_error_m_.store(e); };
      tracking_error_m_.store(std::numeric_limits<double>::quiet_NaN());
      auto link = vehicle::session_client_options(config_.clients_port, 5.0);
      auto started = trajectory_.start(
          link, *dashboard_.trajectory, options, [this](const std::string& text) { log_.add(Severity::Info, text); },
          [this](const Expected<vehicle::FlightResult>& r) {
            if (!r) return log_.add_outcome(Severity::Error, "trajectory: " + r.error().message);
            const Severity s = r->ok() ? Severity::Notice : r->stopped ? Severity::Warning : Severity::Error;
            log_.add(s, r->text());
            log_.add_outcome(s, r->stopped ? std::string("trajectory stopped in ") + vehicle::to_string(r->state)
                                           : std::string("trajectory ended: ") + (r->ok() ? "done" : vehicle::to_string(r->state)));
          });
      if (!started) log_.add_outcome(Severity::Error, "f: " + started.error().message);
      return;
    }
    case Action::Arm:
    case Action::Disarm:
    case Action::ForceDisarm:
    case Action::Takeoff:
    case Action::Land:
    case Action::Shell: board_.perform(action, argument); return;
  }
}

namespace {

/// A loop latency figure (engine/hil/loop_latency.h) in ms; degraded above one step in lockstep,
/// where the board answers each step (outside it the board's own stream sets the pace).
LinkField loop_latency_field(const char* label, const hil::LoopLatencySummary& l, double value_us) {
  if (l.latency.count == 0) return {label, "-"};
  const bool late = l.lockstep && value_us > kStepPeriod_s * 1e6;
  return {label, format("%.2f ms", value_us / 1000.0), late ? Health::Degraded : Health::Good};
}

LatencyPanel latency_panel(const hil::LoopLatencySummary& l) {
  LatencyPanel p;
  p.matched = l.lockstep ? "by echo" : "next message";
  p.count = l.latency.count;
  p.p50_us = l.latency.p50_us;
  p.p95_us = l.latency.p95_us;
  p.p99_us = l.latency.p99_us;
  p.max_us = l.latency.max_us;
  p.limit_us = l.lockstep ? kStepPeriod_s * 1e6 : 0;
  auto edge = [](uint64_t us) { return us >= 1000 ? format("%llu ms", static_cast<unsigned long long>(us / 1000)) : format("%llu us", static_cast<unsigned long long>(us)); };
  for (const auto& b : l.latency.bins)
    p.bins.push_back({b.hi_us == 0 ? ">=" + edge(b.lo_us) : "<" + edge(b.hi_us), b.count});
  return p;
}

}  // namespace

DashboardModel SimDashboard::collect() {
  const hil::SessionSnapshot s = session_.snapshot();
  DashboardModel m;
  m.title = dashboard_.title;
  m.keys = config_.clients_port == 0 ? "prx" : "adtlprfsx";  // --clients 0: nothing reaches the board (faults still do)
  const double pace = s.speed > 0 ? s.speed : (s.recent_real_time_factor > 0 ? s.recent_real_time_factor : 1.0);
  if (s.paused) {
    m.state = "PAUSED";
    m.state_health = Health::Degraded;
  } else if (!s.connected && s.send_errors > 0) {
    m.state = "cannot send to the flight stack (see Messages)";
    m.state_health = Health::Bad;
  } else if (!s.connected) {
    m.state = "no answer from the flight stack";
    m.state_health = Health::Bad;
  } else {
    m.state = "running";
  }
  // Injected faults (--fault, --scenario, the x menu): listed in the menu, named on the state line.
  m.active_faults = active_faults_from(s.faults, s.sim_time_s);
  if (!m.active_faults.empty()) {
    m.state += "; " + active_faults_text(m.active_faults);
    if (m.state_health == Health::Good) m.state_health = Health::Degraded;
  }
  m.clock = format("sim %.1f s  rtf %.2f", s.sim_time_s, s.recent_real_time_factor);
  const std::string pace_text = s.speed > 0 ? format("--speed %g", s.speed) : "the measured real-time factor";
  m.paths = paths_from(s.paths, s.paused,
                       "expected at " + pace_text + (s.lockstep ? ", lockstep" : "") + "; loss: frames from the board");


  board_.fill(m, pace);
  if (config_.clients_port == 0) m.vehicle->armed = s.armed;  // no autopilot link: the actuator flags' armed bit
  if (m.vehicle->landed.empty()) m.vehicle->in_air = !s.on_ground;  // the autopilot has not said: the truth
  m.vehicle->motors = s.motor_commands;
  m.vehicle->rotor_speed_rad_s = s.rotor_speed_rad_s;
  for (const auto& r : config_.vehicle.rotors) m.vehicle->rotor_max_rad_s = std::max(m.vehicle->rotor_max_rad_s, r.max_rot_velocity_rad_s);
  if (s.steps > 0) m.vehicle->truth_altitude_m = s.altitude_m;  // above home at rest, as the estimate

  m.latency = latency_panel(s.loop_latency);

  m.trajectory_running = trajectory_.running();
  if (m.trajectory_running) m.busy = "flying " + dashboard_.trajectory_file;
  m.messages = log_.lines();
  m.outcome = log_.outcome();

  auto sum = [](const std::map<std::string, hil::StreamCount>& streams) {
    uint64_t n = 0;
    for (const auto& [name, c] : streams) n += c.count;
    return n;
  };
  auto count = [](uint64_t n) { return std::to_string(n); };
  m.link_partner = s.partner.empty() ? "" : s.partner + (s.connected ? "" : " (no answer)");
  m.link_health = s.connected ? Health::Good : Health::Bad;
  auto flag = [](uint64_t n) { return n > 0 ? Health::Degraded : Health::Good; };
  const uint64_t ignored = s.ignored_other_address + s.ignored_other_sysid;
  // The first eight fit 80x24; wider terminals show them all.
  m.link = {
      {"rtf", format("%.2f", s.recent_real_time_factor)},
      {"late", count(s.late_ticks), flag(s.late_ticks)},
      loop_latency_field("loop p99", s.loop_latency, s.loop_latency.latency.p99_us),
      {"out", count(sum(s.sent))},
      {"in", count(sum(s.received))},
      {"ignored", count(ignored), flag(ignored)},
      {"clamped", count(s.actuator_clamped), flag(s.actuator_clamped)},
      {"crc err", count(s.crc_errors + s.parse_errors), flag(s.crc_errors + s.parse_errors)},
      {"lockstep", s.lockstep ? count(s.lockstep_fallbacks) + " fb" : "off", flag(s.lockstep_fallbacks)},
      {"send err", count(s.send_errors), flag(s.send_errors)},
      {"avg rtf", format("%.2f", s.real_time_factor)},
      {"max late", format("%.1f ms", s.max_lateness_ms)},
      {"clients", count(s.clients)},
      {"routed", count(s.routed_to_board) + "/" + count(s.routed_to_clients)},
      {"act timeout", count(s.actuator_timeouts), flag(s.actuator_timeouts)},
      {"resets", count(s.resets)},
      {"imu sat", count(s.imu_accel_saturated + s.imu_gyro_saturated), flag(s.imu_accel_saturated + s.imu_gyro_saturated)},
      {"touchdowns", count(s.touchdowns)},
      loop_latency_field("loop p50", s.loop_latency, s.loop_latency.latency.p50_us),
      loop_latency_field("loop max", s.loop_latency, s.loop_latency.latency.max_us),
  };
  // On simulated time: the graphs hold still while paused and show simulated seconds at any --speed.
  graphs_.add(s.sim_time_s, m, m.trajectory_running ? std::optional<double>(tracking_error_m_.load()) : std::nullopt);
  m.graphs = graphs_.panel();
  return m;
}

}  // namespace hitl::tui
