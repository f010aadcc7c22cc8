// A VehicleLink to a scripted board on loopback (header only: the tests that use it link hitl_vehicle).
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <string>

#include "engine/vehicle/vehicle_link.h"

namespace hitl::test {

/// Connected to 127.0.0.1:`port` from an ephemeral port, discovery within 3 s; `stop` ends its waits.
inline std::unique_ptr<vehicle::VehicleLink> connect_to(uint16_t port, const std::atomic<bool>* stop = nullptr) {
  vehicle::LinkOptions o;
  o.connect = "udp:127.0.0.1:" + std::to_string(port);
  o.local_port = 0;
  o.timeout_s = 3;
  o.stop = stop;
  auto link = vehicle::VehicleLink::connect(o);
  EXPECT_TRUE(link.ok()) << link.error().message;
  return link ? std::move(link.value()) : nullptr;
}

}  // namespace hitl::test
