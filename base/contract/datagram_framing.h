// Datagrams on a byte stream and back: the one implementation of tunnel_protocol.h's format,
// used by hitl-adb-relay on the board and by hitl on the host. Portable C++17, no I/O.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/contract/tunnel_protocol.h"

namespace hitl::adb {

struct Hello {
  uint16_t version = kProtocolVersion;
  uint16_t max_datagram_bytes = static_cast<uint16_t>(kMaxDatagram_bytes);
};

/// Appends the 12-byte hello to `out`.
void append_hello(std::vector<uint8_t>& out, const Hello& hello = Hello{});
/// Reads a hello from its 12 bytes; an error naming what is wrong when they are not one.
struct HelloResult {
  std::optional<Hello> hello;
  std::string error;  ///< empty when `hello` is set
};
HelloResult parse_hello(const uint8_t* bytes, std::size_t size);
/// Whether the first `size` bytes of a stream (fewer than a hello) can still start a hello.
bool starts_like_hello(const uint8_t* bytes, std::size_t size);
/// "not a hitl adb tunnel: the stream starts with 'GET / HT', not 'hitl-adb'".
std::string not_a_tunnel_error(const uint8_t* bytes, std::size_t size);

/// Appends one frame (header + payload) to `out`; false when the payload is longer than
/// kMaxDatagram_bytes (nothing appended).
bool append_frame(std::vector<uint8_t>& out, Channel channel, const uint8_t* payload, std::size_t size);

/// A control message's 9-byte payload, and back (nullopt when it is not one).
struct ControlMessage {
  ControlType type = ControlType::Ping;
  uint64_t value = 0;
};
void append_control_frame(std::vector<uint8_t>& out, const ControlMessage& message);
std::optional<ControlMessage> parse_control(const uint8_t* payload, std::size_t size);

/// Splits a stream back into frames, whatever the reads' boundaries (a frame split across reads,
/// many frames in one read). Holds at most one partial frame (bounded). A frame with an unknown
/// channel or a length over the limit is malformed: the decoder reports it once and stays failed,
/// since nothing after it can be trusted to start on a frame boundary.
class FrameDecoder {
 public:
  explicit FrameDecoder(std::size_t max_payload_bytes = kMaxDatagram_bytes);

  /// Called for each complete frame; the payload is valid only during the call.
  struct Sink {
    virtual ~Sink() = default;
    virtual void on_frame(Channel channel, const uint8_t* payload, std::size_t size) = 0;
  };
  /// Decodes `size` bytes, calling sink.on_frame per frame. Returns false (and sets error()) when
  /// the stream is malformed; frames before the malformed one have been delivered.
  bool feed(const uint8_t* data, std::size_t size, Sink& sink);

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  /// Bytes of a frame received in part, waiting for the rest.
  std::size_t buffered() const { return buffer_.size(); }
  uint64_t frames() const { return frames_; }

 private:
  bool check_header(const uint8_t* header);

  std::size_t max_payload_;
  std::vector<uint8_t> buffer_;  ///< a partial frame: header first, then payload
  std::string error_;
  uint64_t frames_ = 0;
};

}  // namespace hitl::adb
