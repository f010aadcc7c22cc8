#include "cli/link_options.h"

#include "cli/number_check.h"
#include "engine/net/link_spec.h"

namespace hitl::cli {

void add_link_options(CLI::App* command, vehicle::LinkOptions& o) {
  const char* group = "Connection";
  command->add_option("--connect", o.connect,
                      std::string("auto (a running hitl sim/bridge on 127.0.0.1:14600, else the board's GCS instance), ") +
                          net::kLinkGrammar)
      ->capture_default_str()->group(group);
  command->add_option("-i,--target-ip", o.target_ip, "The board's IP for the direct path")->capture_default_str()->group(group);
  command->add_option("--port", o.gcs_port, "The board's GCS MAVLink instance")->capture_default_str()
      ->check(number_in(1, 65535))->group(group);
  command->add_option("--local-port", o.local_port,
                      "Local port for direct links: fixed, since PX4 answers only the first port it heard")
      ->capture_default_str()->check(number_in(1, 65535))->group(group);
  command->add_option("--session-port", o.session_port, "The client port of a running hitl sim / hitl bridge (its --clients)")
      ->capture_default_str()->check(number_in(1, 65535))->group(group);
  command->add_option("--sysid", o.sysid, "The autopilot's system id, when several answer")->check(number_in(1, 255))->group(group);
  command->add_option("--timeout", o.timeout_s, "Seconds to wait for the autopilot's HEARTBEAT")->capture_default_str()
      ->check(positive_number())->group(group);
}

}  // namespace hitl::cli
