// A scripted autopilot on loopback for the vehicle clients' tests: HEARTBEAT every 100 ms (PX4,
// with the base and custom mode the test sets), `script` answers each frame it receives, and
// `tick` (when given) runs every 20 ms on the same thread, for streams the test makes up.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <thread>

#include "tests/support/mavlink_peer.h"

namespace hitl::test {

class ScriptedBoard {
 public:
  using Script = std::function<void(const mavlink::Frame&, MavlinkPeer&)>;
  using Tick = std::function<void(MavlinkPeer&)>;
  explicit ScriptedBoard(Script script, Tick tick = {});
  ~ScriptedBoard();
  ScriptedBoard(const ScriptedBoard&) = delete;
  ScriptedBoard& operator=(const ScriptedBoard&) = delete;

  uint16_t port() { return peer_.endpoint().local_address().port(); }
  std::atomic<uint8_t> base_mode{0};     ///< HEARTBEAT's base_mode (128: armed)
  std::atomic<uint32_t> custom_mode{0};  ///< HEARTBEAT's custom_mode (PX4: main << 16 | sub << 24)

 private:
  MavlinkPeer peer_;
  Script script_;
  Tick tick_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

}  // namespace hitl::test
