#include "target/adb-relay/relay_options.h"

#include <arpa/inet.h>

#include <cstdlib>

namespace hitl::adb {
namespace {

bool parse_port(const std::string& text, bool allow_zero, uint16_t* out) {
  if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos) return false;
  const long v = std::strtol(text.c_str(), nullptr, 10);
  if (v > 65535 || (v == 0 && !allow_zero)) return false;
  *out = static_cast<uint16_t>(v);
  return true;
}

}  // namespace

std::string relay_usage() {
  const RelayConfig d;
  return std::string(
             "Usage: hitl-adb-relay [options]\n"
             "\n"
             "The board side of hitl's adb tunnel. `adb forward` carries TCP only; hitl (hitl sim --adb, hitl bridge\n"
             "--adb) frames each UDP datagram onto one TCP stream through `adb forward`, and this relay turns it back\n"
             "into UDP to the board's ports, and the replies back again. hitl pushes and starts it by itself when it\n"
             "is missing; you run it by hand only to troubleshoot. One host at a time: a new connection replaces the\n"
             "current one. Tunnel protocol version ") +
         std::to_string(kProtocolVersion) +
         " (docs/adb.md).\n"
         "\n"
         "Options:\n"
         "  --port N             TCP port to listen on (default " + std::to_string(d.tcp_port) + ")\n"
         "  --bind ADDR          Address to listen on (default " + d.bind_address + ": adbd connects from the board)\n"
         "  --hil-port N         The HIL channel's UDP port on 127.0.0.1 (default " + std::to_string(d.hil_port) + ")\n"
         "  --vio-port N         The VIO channel's UDP port on 127.0.0.1 (default " + std::to_string(d.vio_port) + ")\n"
         "  --gcs-port N         The GCS channel's UDP port on 127.0.0.1 (default " + std::to_string(d.gcs_port) + ")\n"
         "  --hil-source-port N  Send HIL from this UDP port (default " + std::to_string(d.hil_source_port) +
         "; PX4 answers only the first port it heard; 0: any)\n"
         "  --gcs-source-port N  Send GCS from this UDP port (default " + std::to_string(d.gcs_source_port) + "; 0: any)\n"
         "  --daemon             Detach once listening (prints the pid), log to --log\n"
         "  --log FILE           Append the log to FILE (default: stderr; " + kRelayDaemonLogPath + " with --daemon)\n"
         "  --verbose            Also log the counters every 10 s, each failed send and each oversize datagram\n"
         "  --version            Print the version and the tunnel protocol version\n"
         "  --help               This text\n"
         "\n"
         "Exit codes: 0 stopped by SIGTERM/SIGINT, 1 cannot listen or bind, 2 bad usage.\n";
}

ParsedRelayOptions parse_relay_options(const std::vector<std::string>& args) {
  ParsedRelayOptions r;
  auto& o = r.options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string* out) {
      if (i + 1 >= args.size()) {
        r.error = a + ": needs a value";
        return false;
      }
      *out = args[++i];
      return true;
    };
    auto port = [&](uint16_t* out, bool allow_zero) {
      std::string text;
      if (!value(&text)) return false;
      if (!parse_port(text, allow_zero, out)) {
        r.error = a + ": '" + text + "' is not a port number (" + (allow_zero ? "0" : "1") + "..65535)";
        return false;
      }
      return true;
    };
    bool ok = true;
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--version") o.version = true;
    else if (a == "--verbose" || a == "-v") o.relay.verbose = true;
    else if (a == "--daemon") o.daemon = true;
    else if (a == "--port") ok = port(&o.relay.tcp_port, true);
    else if (a == "--bind") ok = value(&o.relay.bind_address);
    else if (a == "--hil-port") ok = port(&o.relay.hil_port, false);
    else if (a == "--vio-port") ok = port(&o.relay.vio_port, false);
    else if (a == "--gcs-port") ok = port(&o.relay.gcs_port, false);
    else if (a == "--hil-source-port") ok = port(&o.relay.hil_source_port, true);
    else if (a == "--gcs-source-port") ok = port(&o.relay.gcs_source_port, true);
    else if (a == "--log") ok = value(&o.log_path);
    else {
      r.error = "unknown option '" + a + "' (--help lists them)";
      ok = false;
    }
    if (!ok) return r;
  }
  in_addr bind_address{};
  if (inet_pton(AF_INET, o.relay.bind_address.c_str(), &bind_address) != 1) {
    r.error = "--bind: '" + o.relay.bind_address + "' is not an IPv4 address";
    return r;
  }
  if (o.daemon && o.log_path.empty()) o.log_path = kRelayDaemonLogPath;
  return r;
}

}  // namespace hitl::adb
