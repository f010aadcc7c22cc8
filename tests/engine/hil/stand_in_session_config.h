// The session config the in-process session tests share: a session to a stand-in board on
// 127.0.0.1, without VIO or a client port, the x500 in the default world, with faults parsed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/faults/fault_spec.h"
#include "engine/hil/session.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/process.h"

namespace hitl::hil::test_session {

/// `faults` as --fault takes them; one that does not parse fails the test and is left out.
inline SessionConfig stand_in_session_config(uint16_t board_port, const std::vector<std::string>& faults = {}) {
  SessionConfig c;
  c.target_ip = "127.0.0.1";
  c.hil_port = board_port;
  c.local_port = test::free_udp_port();
  c.vio = false;
  c.clients_port = 0;
  c.vehicle = model::x500_vehicle_config();
  c.world = model::default_world_config();
  for (const auto& f : faults) {
    auto spec = faults::parse_fault(f);
    EXPECT_TRUE(spec) << spec.error().message;
    if (spec) c.faults.push_back(*spec);
  }
  return c;
}

}  // namespace hitl::hil::test_session
