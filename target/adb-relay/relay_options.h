// hitl-adb-relay's command line: `--port`, `--verbose`, the board ports, `--daemon`. Later options
// override earlier ones (the host's start command can be extended).
#pragma once

#include <string>
#include <vector>

#include "target/adb-relay/relay.h"

namespace hitl::adb {

struct RelayOptions {
  RelayConfig relay;
  bool help = false;
  bool version = false;
  bool daemon = false;     ///< --daemon: detach once listening (how hitl starts it through `adb shell`)
  std::string log_path;    ///< --log FILE (default: stderr; kDefaultDaemonLog with --daemon)
};

/// Parses argv (without the program name); an error naming the option and the problem.
struct ParsedRelayOptions {
  RelayOptions options;
  std::string error;  ///< empty on success
};
ParsedRelayOptions parse_relay_options(const std::vector<std::string>& args);

/// The --help text.
std::string relay_usage();

}  // namespace hitl::adb
