#include "base/contract/framed_stream.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace hitl::adb {

class FramedStream::Dispatch : public FrameDecoder::Sink {
 public:
  explicit Dispatch(Events& events) : events_(events) {}
  void on_frame(Channel channel, const uint8_t* payload, std::size_t size) override { events_.on_frame(channel, payload, size); }

 private:
  Events& events_;
};

FramedStream::FramedStream(int fd, std::size_t max_backlog_bytes)
    : fd_(fd), max_backlog_(max_backlog_bytes), read_buffer_(64 * 1024) {
  const int flags = ::fcntl(fd_, F_GETFL, 0);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  const int on = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);  // a datagram goes out when it comes in
}

FramedStream::~FramedStream() {
  if (fd_ >= 0) ::close(fd_);
}

void FramedStream::queue_hello(const Hello& hello) { append_hello(out_, hello); }

FramedStream::Queued FramedStream::queue(Channel channel, const uint8_t* payload, std::size_t size) {
  if (size > kMaxDatagram_bytes) return Queued::TooLarge;
  if (backlog() + kFrameHeaderSize_bytes + size > max_backlog_) return Queued::BacklogFull;
  append_frame(out_, channel, payload, size);
  return Queued::Yes;
}

void FramedStream::queue_control(const ControlMessage& message) { append_control_frame(out_, message); }

std::string FramedStream::flush() {
  while (out_offset_ < out_.size()) {
    const ssize_t n = ::send(fd_, out_.data() + out_offset_, out_.size() - out_offset_, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      out_offset_ += static_cast<std::size_t>(n);
      bytes_out_ += static_cast<uint64_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    return std::string("sending failed: ") + (n < 0 ? std::strerror(errno) : "connection closed");
  }
  if (out_offset_ == out_.size()) {
    out_.clear();
    out_offset_ = 0;
  } else if (out_offset_ > out_.size() / 2) {
    out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(out_offset_));
    out_offset_ = 0;
  }
  return {};
}

FramedStream::ReadResult FramedStream::read(Events& events) {
  Dispatch dispatch(events);
  // A bounded number of reads per call, so one busy stream cannot starve the caller's other sockets.
  for (int reads = 0; reads < 16; ++reads) {
    const ssize_t n = ::recv(fd_, read_buffer_.data(), read_buffer_.size(), MSG_DONTWAIT);
    if (n == 0) {
      error_ = "the other end closed the connection";
      return ReadResult::Closed;
    }
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return ReadResult::Open;
      error_ = std::string("connection lost: ") + std::strerror(errno);
      return ReadResult::Closed;
    }
    bytes_in_ += static_cast<uint64_t>(n);
    const uint8_t* data = read_buffer_.data();
    std::size_t size = static_cast<std::size_t>(n);
    if (!peer_hello_) {
      const std::size_t take = std::min(size, kHelloSize_bytes - hello_in_.size());
      hello_in_.insert(hello_in_.end(), data, data + take);
      data += take;
      size -= take;
      if (hello_in_.size() < kHelloSize_bytes) {
        // A wrong magic shows in its first bytes: say so now rather than wait for twelve.
        if (!starts_like_hello(hello_in_.data(), hello_in_.size())) {
          error_ = not_a_tunnel_error(hello_in_.data(), hello_in_.size());
          return ReadResult::Failed;
        }
        continue;
      }
      auto parsed = parse_hello(hello_in_.data(), hello_in_.size());
      if (!parsed.hello) {
        error_ = parsed.error;
        return ReadResult::Failed;
      }
      peer_hello_ = parsed.hello;
      if (std::string refused = events.on_hello(*peer_hello_); !refused.empty()) {
        error_ = std::move(refused);
        return ReadResult::Failed;
      }
    }
    if (size > 0 && !decoder_.feed(data, size, dispatch)) {
      error_ = decoder_.error();
      return ReadResult::Failed;
    }
  }
  return ReadResult::Open;
}

}  // namespace hitl::adb
