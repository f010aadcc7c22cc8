// voxl-hitl-vio-server: MAVLink ODOMETRY over UDP -> ModalAI's VIO on the MPA pipes hitl_vio and
// hitl_vio_extended. Wiring only: options, the configuration file, signals, exit codes.
#include <getopt.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "target/vio-server/pipe_server.h"
#include "target/vio-server/server_status.h"
#include "target/vio-server/vio_server.h"
#include "target/vio-server/vio_server_config.h"

#ifndef HITL_VERSION
#error "HITL_VERSION must be defined by the build"
#endif

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;

void print_help() {
  std::cout <<
      "Usage: voxl-hitl-vio-server [options]\n"
      "\n"
      "Receives MAVLink ODOMETRY over UDP (hitl sim sends it at 250 Hz) and publishes each pose as\n"
      "ModalAI's VIO: vio_data_t on the MPA pipe hitl_vio, ext_vio_data_t on hitl_vio_extended, for\n"
      "voxl-vision-hub with en_hitl. The configuration file holds \"receiver_ip\" (default 0.0.0.0)\n"
      "and \"receiver_port\" (default 14570); a missing file is created with the defaults.\n"
      "\n"
      "Options:\n"
      "  -c, --config PATH       configuration file (default /etc/modalai/voxl-hitl-vio-server.conf)\n"
      "  -m, --mpa-dir DIR       MPA base directory the pipes are made in (default /run/mpa/)\n"
      "      --vision-hub-fifo   make hitl_vio the single FIFO <mpa-dir>/hitl_vio that voxl-vision-hub's\n"
      "                          en_hitl reader opens, instead of an MPA pipe directory\n"
      "      --status-file PATH  where the running server reports once a second\n"
      "                          (default /run/voxl-hitl-vio-server/status.json)\n"
      "  -s, --status            print the running server's ODOMETRY rate and counts and exit\n"
      "                          (exit 1 when no server is running)\n"
      "      --json              with --status: the report as one JSON object\n"
      "  -h, --help              this text\n"
      "      --version           the version\n"
      "\n"
      "SIGTERM or SIGINT stops the server; it removes its pipes. Exit codes: 0 stopped cleanly,\n"
      "1 could not serve (port in use, pipes), 2 bad usage or configuration.\n";
}

void log_line(const std::string& text) {
  // One line per event on stderr; journald adds the time when run as a service.
  std::fprintf(stderr, "voxl-hitl-vio-server: %s\n", text.c_str());
  std::fflush(stderr);
}

int print_status(const std::string& status_file, bool json) {
  auto report = hitl::vio::read_status_file(status_file);
  if (!report.ok()) {
    if (json) {
      std::cout << nlohmann::json{{"running", false}, {"error", report.error().message}}.dump() << "\n";
    } else {
      std::cerr << report.error().message << "\n";
    }
    return kExitFailed;
  }
  if (json) {
    auto doc = hitl::vio::to_json(report->status);
    doc["running"] = true;
    doc["report_age_s"] = report->age_s;
    std::cout << doc.dump() << "\n";
  } else {
    std::cout << hitl::vio::format_status(report.value());
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  std::string config_path = hitl::vio::kDefaultConfigPath;
  hitl::vio::VioServerOptions options;
  bool status = false;
  bool json = false;
  enum { kOptStatusFile = 1000, kOptJson, kOptVersion, kOptVisionHubFifo };
  const option long_options[] = {{"config", required_argument, nullptr, 'c'},
                                 {"mpa-dir", required_argument, nullptr, 'm'},
                                 {"status-file", required_argument, nullptr, kOptStatusFile},
                                 {"status", no_argument, nullptr, 's'},
                                 {"vision-hub-fifo", no_argument, nullptr, kOptVisionHubFifo},
                                 {"json", no_argument, nullptr, kOptJson},
                                 {"help", no_argument, nullptr, 'h'},
                                 {"version", no_argument, nullptr, kOptVersion},
                                 {nullptr, 0, nullptr, 0}};
  opterr = 0;
  for (;;) {
    const int c = ::getopt_long(argc, argv, ":c:m:sh", long_options, nullptr);
    if (c == -1) break;
    switch (c) {
      case 'c': config_path = optarg; break;
      case 'm': options.mpa_dir = optarg; break;
      case kOptStatusFile: options.status_file = optarg; break;
      case 's': status = true; break;
      case kOptJson: json = true; break;
      case kOptVisionHubFifo: options.vision_hub_fifo = true; break;
      case 'h': print_help(); return kExitOk;
      case kOptVersion: std::cout << "voxl-hitl-vio-server " << HITL_VERSION << "\n"; return kExitOk;
      case ':':
        std::cerr << "voxl-hitl-vio-server: " << argv[optind - 1] << " needs a value (see --help)\n";
        return kExitUsage;
      default:
        std::cerr << "voxl-hitl-vio-server: unknown option " << argv[optind - 1] << " (see --help)\n";
        return kExitUsage;
    }
  }
  if (optind < argc) {
    std::cerr << "voxl-hitl-vio-server: unexpected argument \"" << argv[optind] << "\" (see --help)\n";
    return kExitUsage;
  }
  if (json && !status) {
    std::cerr << "voxl-hitl-vio-server: --json goes with --status\n";
    return kExitUsage;
  }
  if (status) return print_status(options.status_file, json);
  if (options.mpa_dir.empty() || options.mpa_dir[0] != '/') {
    std::cerr << "voxl-hitl-vio-server: --mpa-dir must be an absolute path, not \"" << options.mpa_dir << "\"\n";
    return kExitUsage;
  }

  auto loaded = hitl::vio::load_or_create_config(config_path);
  if (!loaded.ok()) {
    log_line(loaded.error().message);
    return kExitUsage;
  }
  if (loaded->created) log_line("created " + config_path + " with the defaults");
  options.config = loaded->config;

  // Signals arrive on a descriptor the loop polls; a write to a departed client is an EPIPE, not a signal.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGHUP);
  ::sigprocmask(SIG_BLOCK, &stop_signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);
  const int signal_fd = ::signalfd(-1, &stop_signals, SFD_CLOEXEC);
  if (signal_fd < 0) {
    log_line("cannot create a signal descriptor");
    return kExitFailed;
  }

  auto server = hitl::vio::VioServer::start(options, log_line);
  if (!server.ok()) {
    log_line(server.error().message);
    return kExitFailed;
  }
  auto ran = server.value()->run(signal_fd);
  server.value().reset();
  ::close(signal_fd);
  if (!ran.ok()) {
    log_line(ran.error().message);
    return kExitFailed;
  }
  return kExitOk;
}
