// One end of the tunnel's TCP stream: our hello out, the peer's hello in, then datagrams both
// ways as frames (datagram_framing.h). Non-blocking and bounded: what the socket does not take at
// once waits in a send backlog of at most max_backlog bytes; a datagram that does not fit is
// dropped and counted (UDP's own semantics: late sensor data is worth less than none).
// Shared by hitl-adb-relay and hitl's host side. Portable C++17 and POSIX sockets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/contract/datagram_framing.h"

namespace hitl::adb {

class FramedStream {
 public:
  static constexpr std::size_t kDefaultMaxBacklog_bytes = 64 * 1024;

  /// Takes a connected stream socket (closed by the destructor) and makes it non-blocking.
  explicit FramedStream(int fd, std::size_t max_backlog_bytes = kDefaultMaxBacklog_bytes);
  ~FramedStream();
  FramedStream(const FramedStream&) = delete;
  FramedStream& operator=(const FramedStream&) = delete;

  int fd() const { return fd_; }

  void queue_hello(const Hello& hello = Hello{});
  enum class Queued { Yes, TooLarge, BacklogFull };
  /// Frames one datagram into the backlog (flush() sends it).
  Queued queue(Channel channel, const uint8_t* payload, std::size_t size);
  void queue_control(const ControlMessage& message);
  /// Bytes waiting to be written; poll for POLLOUT while this is not zero.
  std::size_t backlog() const { return out_.size() - out_offset_; }
  /// Writes what the socket takes now, without blocking. An error text when the connection failed.
  std::string flush();

  struct Events {
    virtual ~Events() = default;
    /// The peer's hello; return an error text to refuse the stream (read() then fails with it).
    virtual std::string on_hello(const Hello& hello) = 0;
    virtual void on_frame(Channel channel, const uint8_t* payload, std::size_t size) = 0;
  };
  enum class ReadResult { Open, Closed, Failed };
  /// Reads what is waiting without blocking: the peer's hello first, then frames. Closed when the
  /// peer closed the stream, Failed on a malformed stream or a refused hello; error() says which.
  ReadResult read(Events& events);
  const std::string& error() const { return error_; }
  const std::optional<Hello>& peer_hello() const { return peer_hello_; }

  uint64_t bytes_in() const { return bytes_in_; }
  uint64_t bytes_out() const { return bytes_out_; }

 private:
  class Dispatch;

  int fd_ = -1;
  std::size_t max_backlog_;
  std::vector<uint8_t> out_;
  std::size_t out_offset_ = 0;
  std::vector<uint8_t> hello_in_;
  std::optional<Hello> peer_hello_;
  FrameDecoder decoder_;
  std::vector<uint8_t> read_buffer_;
  std::string error_;
  uint64_t bytes_in_ = 0;
  uint64_t bytes_out_ = 0;
};

}  // namespace hitl::adb
