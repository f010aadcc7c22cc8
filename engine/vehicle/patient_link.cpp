#include "engine/vehicle/patient_link.h"

#include <chrono>
#include <thread>

#include "base/common/clock.h"

namespace hitl::vehicle {

std::unique_ptr<VehicleLink> connect_patiently(const LinkOptions& options, const std::atomic<bool>& stop,
                                               const std::function<void(const std::string&)>& waiting) {
  LinkOptions stoppable = options;
  stoppable.stop = &stop;  // a discovery in progress ends when asked to stop
  while (!stop.load()) {
    const double started_s = monotonic_s();
    auto link = VehicleLink::connect(stoppable);
    if (link) return std::move(link.value());
    if (waiting) waiting(link.error().message);
    // A refused port fails at once: do not spin, try again about every second.
    while (!stop.load() && monotonic_s() - started_s < 1.0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return nullptr;
}

LinkOptions session_client_options(uint16_t port, double timeout_s) {
  LinkOptions o;
  o.connect = "udp:127.0.0.1:" + std::to_string(port);
  o.local_port = 0;
  o.session_port = port;
  o.timeout_s = timeout_s;
  return o;
}

}  // namespace hitl::vehicle
