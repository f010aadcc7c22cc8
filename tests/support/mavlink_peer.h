// A MAVLink peer on loopback for tests: sends typed messages (optionally paced at a
// rate with absolute deadlines) and collects what it receives.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::test {

class MavlinkPeer {
 public:
  /// Binds 127.0.0.1:`local_port` (0: ephemeral) and sends to `peer_port` on 127.0.0.1 (0: none yet).
  MavlinkPeer(uint16_t local_port, uint16_t peer_port, uint8_t sysid = 1, uint8_t compid = 1);
  ~MavlinkPeer();

  template <class M>
  void send(const M& message) {
    mavlink::FrameBuffer buf;
    const std::size_t n = encoder_.encode(message, buf);
    send_bytes({buf.data(), n});
  }
  void send_bytes(std::span<const uint8_t> bytes);

  /// Calls `make_and_send` at `rate_hz` on absolute deadlines until stop() or `duration`.
  void start_paced(double rate_hz, std::chrono::milliseconds duration, std::function<void(MavlinkPeer&)> make_and_send);
  void stop();
  uint64_t paced_sent() const { return paced_sent_.load(); }

  /// Receives for up to `timeout`, returning every frame that arrived.
  std::vector<mavlink::Frame> receive_for(std::chrono::milliseconds timeout);
  net::UdpEndpoint& endpoint() { return endpoint_; }
  mavlink::FrameEncoder& encoder() { return encoder_; }

 private:
  net::UdpEndpoint endpoint_;
  mavlink::MessageSet messages_;
  mavlink::FrameEncoder encoder_;
  std::mutex send_mutex_;
  std::thread pacer_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> paced_sent_{0};
};

}  // namespace hitl::test
