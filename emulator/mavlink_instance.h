// One PX4 MAVLink instance on UDP, as the board's start script runs them: it binds its port,
// takes the first address and port it hears as its partner and keeps it for good (PX4
// mavlink_main.cpp), and sends its streams at per-message intervals (SET_MESSAGE_INTERVAL).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <vector>
#include <optional>
#include <string>

#include "base/common/expected.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::target {

struct InstanceStats {
  uint64_t frames_in = 0;
  uint64_t frames_out = 0;
  uint64_t not_sent_no_partner = 0;
  uint64_t ignored_not_partner = 0;  ///< heard from someone else than the partner (still used, as PX4 does)
};

class MavlinkInstance {
 public:
  using FrameHandler = std::function<void(const mavlink::Frame&, MavlinkInstance&)>;

  static Expected<std::unique_ptr<MavlinkInstance>> open(const std::string& name, const std::string& bind_address,
                                                         uint16_t port, const mavlink::MessageSet& messages,
                                                         uint8_t sysid, uint8_t compid);

  /// Reads every waiting datagram; frames go to `on_frame` (from any sender, as PX4 uses them).
  void poll(const FrameHandler& on_frame);

  template <class M>
  void send(const M& message) {
    mavlink::FrameBuffer buf;
    const std::size_t n = encoder_.encode(message, buf);
    send_bytes({buf.data(), n});
  }
  void send_bytes(std::span<const uint8_t> bytes);

  /// Stream scheduling: interval per message id (0 = off).
  void set_interval_us(uint32_t msgid, int64_t interval_us);
  std::optional<int64_t> interval_us(uint32_t msgid) const;
  /// The ids whose stream is due at `now_us` (each becomes due again one interval later).
  std::vector<uint32_t> due_streams(int64_t now_us);
  /// Every stream due at the next due_streams() and one interval after it from then on: their phase
  /// set by that moment (lockstep: the first HIL_SENSOR), not by when the board started.
  void restart_streams();

  const std::string& name() const { return name_; }
  uint16_t port() const { return endpoint_.local_address().port(); }
  const std::optional<net::SocketAddress>& partner() const { return endpoint_.partner(); }
  const InstanceStats& stats() const { return stats_; }
  const mavlink::ParserStats& parser_stats() const { return parser_.stats(); }
  int fd() const { return endpoint_.fd(); }

 private:
  MavlinkInstance(std::string name, net::UdpEndpoint endpoint, const mavlink::MessageSet& messages, uint8_t sysid,
                  uint8_t compid);
  struct Stream {
    int64_t interval_us = 0;
    int64_t next_us = 0;
  };
  std::string name_;
  net::UdpEndpoint endpoint_;
  mavlink::FrameParser parser_;
  mavlink::FrameEncoder encoder_;
  std::map<uint32_t, Stream> streams_;
  InstanceStats stats_;
};

}  // namespace hitl::target
