// The UDP side of voxl-hitl-vio-server: a non-blocking socket on receiver_ip:receiver_port whose
// datagrams are parsed with hitl's MAVLink codec. ODOMETRY frames are handed on; everything else
// is counted: valid frames of other messages are ignored, bytes that are not MAVLink (checksum
// errors, garbage, frames cut off by the datagram's end, unknown incompat flags) make the datagram
// "malformed". Nothing from the network is trusted and nothing in it is fatal.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "base/common/expected.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"

namespace hitl::vio {

struct ReceiverCounters {
  uint64_t datagrams = 0;
  uint64_t bytes = 0;
  uint64_t odometry = 0;             ///< ODOMETRY frames decoded
  uint64_t other_messages = 0;       ///< valid frames of other messages, ignored
  uint64_t malformed_datagrams = 0;  ///< datagrams holding anything that is not valid MAVLink
  uint64_t crc_errors = 0;           ///< frames whose checksum did not match
  uint64_t garbage_runs = 0;         ///< runs of bytes that were not part of any frame
  uint64_t truncated = 0;            ///< frames cut off by the end of their datagram
  uint64_t bad_incompat_flags = 0;   ///< v2 frames with incompat flags MAVLink does not define
};

class OdometryReceiver {
 public:
  using OdometryHandler = std::function<void(const mavlink::msg::Odometry&)>;
  /// `why` says what was wrong with the datagram and who sent it ("from 10.0.0.2:5000: 2 checksum errors").
  using MalformedHandler = std::function<void(const std::string& why)>;

  /// Binds UDP `ip`:`port` (0: any free port, for tests).
  static Expected<std::unique_ptr<OdometryReceiver>> open(const std::string& ip, uint16_t port);
  ~OdometryReceiver();

  int fd() const { return fd_; }
  uint16_t port() const { return port_; }
  /// Reads every datagram waiting, without blocking.
  void drain(const OdometryHandler& on_odometry, const MalformedHandler& on_malformed);
  const ReceiverCounters& counters() const { return counters_; }

 private:
  OdometryReceiver(int fd, uint16_t port);
  void handle(const uint8_t* data, std::size_t len, const std::string& sender, const OdometryHandler& on_odometry,
              const MalformedHandler& on_malformed);

  int fd_;
  uint16_t port_;
  mavlink::MessageSet messages_;
  mavlink::FrameParser parser_;
  ReceiverCounters counters_;
};

}  // namespace hitl::vio
