// The PX4 shell over MAVLink (SERIAL_CONTROL device 10, as PX4's mavlink_shell.py): send a line,
// collect the output until the prompt comes back.
#pragma once

#include <string>

#include "base/common/expected.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

class ShellClient {
 public:
  explicit ShellClient(VehicleLink& link) : link_(link) {}
  /// Runs one command line; returns its output without the echoed line and the prompt.
  Expected<std::string> run(const std::string& line, double timeout_s = 5.0);

 private:
  void send_text(const std::string& text);
  VehicleLink& link_;
};

}  // namespace hitl::vehicle
