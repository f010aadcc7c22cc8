// The emulated board's shell (SERIAL_CONTROL, as `hitl shell` and hitl doctor reach PX4's nsh): the
// commands a VOXL2 with the HITL module answers (dsp_hitl, commander, ekf2, mavlink, param, ver)
// and the apps processor's `voxl-hitl-vio-server --status`, with PX4's return codes.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/contract/dsp_hitl_status.h"
#include "emulator/board_impl.h"

namespace hitl::target {

using mavlink::MavResult;

std::string Board::Impl::vio_server_status(bool json) const {
  char buf[256];
  if (!vio) {
    const char* why = "voxl-hitl-vio-server is not running (hitl target: no VIO listener)";
    if (json) std::snprintf(buf, sizeof buf, "{\"running\":false,\"error\":\"%s\"}\n", why);
    else std::snprintf(buf, sizeof buf, "%s\n", why);
    return buf;
  }
  const std::string listen = vio->local_address().to_string();
  if (json)
    std::snprintf(buf, sizeof buf, "{\"running\":true,\"listen\":\"%s\",\"odometry_rate_hz\":%.1f,\"odometry\":%llu}\n",
                  listen.c_str(), vio_rate_hz, static_cast<unsigned long long>(odometry_received));
  else
    std::snprintf(buf, sizeof buf, "voxl-hitl-vio-server (emulated by hitl target): listening on UDP %s\n  ODOMETRY:  %.1f Hz, %llu received\n",
                  listen.c_str(), vio_rate_hz, static_cast<unsigned long long>(odometry_received));
  return buf;
}

ShellResult Board::Impl::shell_command(const std::string& line) {
  std::string cmd = line;
  if (cmd.rfind("qshell ", 0) == 0) cmd = cmd.substr(7);  // on the board qshell runs it on the DSP
  if (cmd == "help")
    return "Builtin commands (hitl target, an emulated VOXL2 board, not PX4):\n"
           "  dsp_hitl start | stop | status (also through qshell)\n  commander status | check | arm | disarm | takeoff | land\n"
           "  ekf2 status\n  mavlink status\n  param show [PATTERN] | param set NAME VALUE\n  ver all\n  help\n"
           "  voxl-hitl-vio-server --status [--json]   (the apps processor's VIO server)\n";
  // dsp_hitl as target/px4's module: status of a stopped module prints "Running: no" with zero
  // counters and returns 1; stop of a stopped module does nothing (ModuleBase).
  if (cmd == "dsp_hitl status")
    return dsp.running() ? ShellResult{dsp.status_text()} : ShellResult{dsp_hitl_status_text(false, {}, {}), 1};
  if (cmd == "dsp_hitl stop") {
    if (dsp.running()) dsp.stop();
    return {};
  }
  if (cmd == "dsp_hitl start") {
    if (dsp.running()) return {"dsp_hitl: already running\n", 1};
    dsp.start();
    return {};
  }
  if (cmd == "commander status") return flight->commander_status();
  if (cmd == "commander check") return flight->commander_check();
  if (cmd.rfind("voxl-hitl-vio-server --status", 0) == 0) return vio_server_status(cmd.find("--json") != std::string::npos);
  if (cmd == "ekf2 status") return flight->ekf2_status();
  if (cmd == "ver all") return "HW arch: VOXL2 (M0197), emulated by hitl target\nFW version: hitl target (PX4 v1.16 dialect)\n";
  if (cmd == "mavlink status") {
    std::string out;
    for (auto* i : instances()) {
      out += "instance #" + std::string(i == hil.get() ? "0" : "2") + " (" + i->name() + "):\n";
      out += "\tUDP (" + std::to_string(i->port()) + ", remote port: " +
             (i->partner() ? std::to_string(i->partner()->port()) : std::string("none")) + ")\n";
      out += "\tpartner: " + (i->partner() ? i->partner()->to_string() : std::string("none yet")) + "\n";
      out += "\trx: " + std::to_string(i->stats().frames_in) + " messages, tx: " + std::to_string(i->stats().frames_out) + " messages\n";
    }
    return out;
  }
  auto result_text = [](const CommandResult& r, const char* what) {
    return r.result == MavResult::Accepted ? std::string(what) + ": ok\n" : (r.text.empty() ? std::string(what) + ": denied" : r.text) + "\n";
  };
  if (cmd == "commander arm") return result_text(flight->arm(false, now_us), "arm");
  if (cmd == "commander arm -f") return result_text(flight->arm(true, now_us), "arm");
  if (cmd == "commander disarm") return result_text(flight->disarm(false, now_us), "disarm");
  if (cmd == "commander takeoff") return result_text(flight->takeoff(NAN, now_us), "takeoff");
  if (cmd == "commander land") return result_text(flight->land(now_us), "land");
  if (cmd.rfind("param show", 0) == 0) {
    std::string pattern = cmd.size() > 11 ? cmd.substr(11) : "";
    const bool prefix = !pattern.empty() && pattern.back() == '*';
    if (prefix) pattern.pop_back();
    std::string out;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const auto& p = params.at(i);
      if (!pattern.empty() && (prefix ? p.name.rfind(pattern, 0) != 0 : p.name != pattern)) continue;
      out += p.name + " [" + std::to_string(i) + "]: " + p.value.to_string() + "\n";
    }
    return out.empty() ? "no parameter matches\n" : out;
  }
  if (cmd.rfind("param set ", 0) == 0) {
    std::istringstream ss(cmd.substr(10));
    std::string name, value;
    ss >> name >> value;
    const auto* current = params.get(name);
    if (current == nullptr) return {"Parameter " + name + " not found.\n", 1};  // PX4's param returns 1
    try {
      auto v = current->type == vehicle::ParamType::Int32 ? vehicle::ParamValue::int32(std::stoi(value))
                                                          : vehicle::ParamValue::real32(std::stof(value));
      auto r = params.set(name, v);
      if (!r) return {"param set: " + r.error().message + "\n", 1};
      ++params_set;
      return name + ": " + v.to_string() + "\n";
    } catch (const std::exception&) {
      return {"param set: '" + value + "' is not a number\n", 1};
    }
  }
  // A command the board has, with a verb it does not know (or `a; b`, which this shell does not
  // split): the module's usage and return 1, as PX4's ModuleBase does, not "command not found".
  const std::string name = cmd.substr(0, cmd.find(' '));
  for (const char* known : {"dsp_hitl", "commander", "ekf2", "mavlink", "param", "ver"}) {
    if (name == known)
      return {name + ": unknown command '" + (cmd.size() > name.size() ? cmd.substr(name.size() + 1) : std::string()) +
                  "' (one command per line; help lists what this shell runs)\n",
              1};
  }
  return "nsh: " + line.substr(0, line.find(' ')) + ": command not found\n";
}

}  // namespace hitl::target
