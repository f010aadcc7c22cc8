// hitl target: an emulated VOXL2 / M0197 board (not PX4) for laptops and CI.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/number_check.h"
#include "emulator/board.h"

namespace hitl::cli {
namespace {

nlohmann::json board_json(const target::BoardSnapshot& s, const char* type) {
  return {{"type", type},
          {"board_time_s", s.board_time_s},
          {"armed", s.armed},
          {"mode", s.mode},
          {"landed_state", s.landed_state},
          {"estimator_ready", s.estimator_ready},
          {"not_ready_reason", s.not_ready_reason},
          {"altitude_m", s.altitude_m},
          {"hil_sensor_received", s.hil_sensor_received},
          {"hil_gps_received", s.hil_gps_received},
          {"odometry_received", s.odometry_received},
          {"actuators_sent", s.actuators_sent},
          {"commands_received", s.commands_received},
          {"params_set", s.params_set},
          {"shell_commands", s.shell_commands},
          {"malformed", s.malformed},
          {"hil_partner", s.hil_partner},
          {"gcs_partner", s.gcs_partner}};
}

class TargetPrinter : public target::Board::Observer {
 public:
  explicit TargetPrinter(const GlobalOptions& global) : global_(global) {}
  void on_event(const target::BoardEvent& e) override {
    if (e.severity != Severity::Info || !global_.quiet) std::cerr << "hitl target: " << (e.severity != Severity::Info ? std::string(to_string(e.severity)) + ": " : "") << e.text << '\n';
  }
  void on_status(const target::BoardSnapshot& s) override {
    if (global_.json) {
      print_json_line(board_json(s, "status"));
    } else if (!global_.quiet && !background_job_of_terminal()) {
      // A background job (`hitl target &`) keeps its status lines to itself: they would bury the
      // next command's output in the same terminal. Its events still show; fg brings the lines back.
      char buf[256];
      std::snprintf(buf, sizeof buf, "t %7.1f s  %s  %-8s %-10s alt %6.2f m  HIL_SENSOR %llu  ODOMETRY %llu  %s",
                    s.board_time_s, s.armed ? "ARMED   " : "disarmed", s.mode.c_str(), s.landed_state.c_str(), s.altitude_m,
                    static_cast<unsigned long long>(s.hil_sensor_received),
                    static_cast<unsigned long long>(s.odometry_received),
                    s.estimator_ready ? "ready to arm" : s.not_ready_reason.c_str());
      std::cerr << buf << '\n';
    }
  }

 private:
  const GlobalOptions& global_;
};

int run_target(const GlobalOptions& global, const target::BoardConfig& config) {
  auto board = target::Board::create(config);
  if (!board) {
    log_error("target", board.error().message);
    return exit_code(board.error());
  }
  const auto& stop = stop_flag_on_signals();
  log_info(global, "hitl target: an EMULATED VOXL2 / M0197 board (not PX4): " + (*board)->describe() + " (Ctrl-C to stop)");
  TargetPrinter printer(global);
  auto end = (*board)->run(stop, printer);
  if (!end) {
    log_error("target", end.error().message);
    return exit_code(end.error());
  }
  const auto s = (*board)->snapshot();
  if (global.json) {
    auto j = board_json(s, "summary");
    j["end"] = *end == target::Board::EndReason::Duration ? "duration" : "stopped";
    print_json_line(j);
  } else {
    std::cout << "board time " << s.board_time_s << " s: " << s.hil_sensor_received << " HIL_SENSOR, " << s.hil_gps_received
              << " HIL_GPS, " << s.odometry_received << " ODOMETRY received; " << s.actuators_sent
              << " HIL_ACTUATOR_CONTROLS sent; " << s.malformed << " malformed\n"
              << s.dsp_hitl_status;
  }
  return kExitOk;
}

}  // namespace

void add_target_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto config = std::make_shared<target::BoardConfig>();
  auto* sub = app.add_subcommand("target",
                                 "Run an EMULATED VOXL2 board (not PX4) that hitl sim and the other commands can fly");
  sub->footer(
      "An emulator for laptops and CI, not PX4: it speaks PX4's MAVLink dialect on the board's ports (HIL 14560,\n"
      "GCS 14558, VIO 14570), runs the spec's HIL split and dsp_hitl republish, estimates from the sensors only,\n"
      "and flies the x500 with a PX4-structured cascade. Its shell answers dsp_hitl/commander/ekf2 status.\n"
      "Example:  hitl target &  hitl sim   # a closed loop on one machine");
  sub->add_option("--bind", config->bind_address, "Local address of the board's sockets")->capture_default_str();
  sub->add_option("--hil-port", config->hil_port, "The HIL MAVLink instance (hitl sim talks to it)")
      ->capture_default_str()->check(number_in(1, 65535));
  sub->add_option("--gcs-port", config->gcs_port, "The GCS MAVLink instance (0: none)")
      ->capture_default_str()->check(number_in(0, 65535));
  sub->add_option("--vio-port", config->vio_port, "voxl-hitl-vio-server's ODOMETRY listener (0: none)")
      ->capture_default_str()->check(number_in(0, 65535));
  sub->add_flag("--lockstep", config->lockstep,
                "Run on HIL_SENSOR.time_usec and answer each HIL_SENSOR (pair with hitl sim --lockstep --speed 0)");
  sub->add_option("--duration", config->duration_s, "Stop after this many seconds of board time")
      ->check(non_negative_number())->type_name("S");
  auto faults = std::make_shared<std::vector<std::string>>();
  std::string fault_list;
  for (const auto& n : target::fault_names()) fault_list += (fault_list.empty() ? "" : ", ") + n;
  sub->add_option("--fault", *faults,
                  "Inject a fault hitl doctor must catch (repeatable): " + fault_list + " (docs/doctor.md)")
      ->type_name("NAME")
      ->check([](const std::string& name) {
        auto f = target::parse_fault(name);
        return f ? std::string() : f.error().message;
      });
  sub->callback([&options, &state, config, faults]() {
    for (const auto& name : *faults) config->faults.set(*target::parse_fault(name));
    state.exit_code = run_target(options, *config);
  });
}

}  // namespace hitl::cli
