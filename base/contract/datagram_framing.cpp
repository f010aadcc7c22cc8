#include "base/contract/datagram_framing.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace hitl::adb {
namespace {

void put_u16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(static_cast<uint8_t>(v >> 8));
  out.push_back(static_cast<uint8_t>(v & 0xFF));
}

uint16_t get_u16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }

/// The first bytes as text for an error message, non-printables as '.'.
std::string printable(const uint8_t* p, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += (p[i] >= 0x20 && p[i] < 0x7F) ? static_cast<char>(p[i]) : '.';
  return s;
}

}  // namespace

void append_hello(std::vector<uint8_t>& out, const Hello& hello) {
  out.insert(out.end(), std::begin(kHelloMagic), std::end(kHelloMagic));
  put_u16(out, hello.version);
  put_u16(out, hello.max_datagram_bytes);
}

HelloResult parse_hello(const uint8_t* bytes, std::size_t size) {
  if (size < kHelloSize_bytes)
    return {std::nullopt, "hello too short: " + std::to_string(size) + " of " + std::to_string(kHelloSize_bytes) + " bytes"};
  if (std::memcmp(bytes, kHelloMagic, sizeof kHelloMagic) != 0) return {std::nullopt, not_a_tunnel_error(bytes, size)};
  Hello h;
  h.version = get_u16(bytes + 8);
  h.max_datagram_bytes = get_u16(bytes + 10);
  return {h, ""};
}

bool starts_like_hello(const uint8_t* bytes, std::size_t size) {
  return std::memcmp(bytes, kHelloMagic, std::min(size, sizeof kHelloMagic)) == 0;
}

std::string not_a_tunnel_error(const uint8_t* bytes, std::size_t size) {
  return "not a hitl adb tunnel: the stream starts with '" + printable(bytes, std::min(size, sizeof kHelloMagic)) +
         "', not 'hitl-adb'";
}

bool append_frame(std::vector<uint8_t>& out, Channel channel, const uint8_t* payload, std::size_t size) {
  if (size > kMaxDatagram_bytes) return false;
  put_u16(out, static_cast<uint16_t>(size));
  out.push_back(static_cast<uint8_t>(channel));
  out.insert(out.end(), payload, payload + size);
  return true;
}

void append_control_frame(std::vector<uint8_t>& out, const ControlMessage& message) {
  uint8_t payload[kControlSize_bytes];
  payload[0] = static_cast<uint8_t>(message.type);
  for (int i = 0; i < 8; ++i) payload[1 + i] = static_cast<uint8_t>(message.value >> (56 - 8 * i));
  append_frame(out, Channel::Control, payload, sizeof payload);
}

std::optional<ControlMessage> parse_control(const uint8_t* payload, std::size_t size) {
  if (size != kControlSize_bytes) return std::nullopt;
  if (payload[0] != static_cast<uint8_t>(ControlType::Ping) && payload[0] != static_cast<uint8_t>(ControlType::Pong))
    return std::nullopt;
  ControlMessage m;
  m.type = static_cast<ControlType>(payload[0]);
  for (int i = 0; i < 8; ++i) m.value = (m.value << 8) | payload[1 + i];
  return m;
}

FrameDecoder::FrameDecoder(std::size_t max_payload_bytes) : max_payload_(max_payload_bytes) {
  buffer_.reserve(kFrameHeaderSize_bytes + max_payload_);
}

bool FrameDecoder::check_header(const uint8_t* header) {
  const std::size_t length = get_u16(header);
  if (!is_known_channel(header[2])) {
    error_ = "malformed frame " + std::to_string(frames_ + 1) + ": unknown channel " + std::to_string(header[2]) +
             " (length " + std::to_string(length) + ")";
    return false;
  }
  if (length > max_payload_) {
    error_ = "malformed frame " + std::to_string(frames_ + 1) + ": " + std::to_string(length) +
             " bytes on the " + to_string(static_cast<Channel>(header[2])) + " channel, over the limit of " +
             std::to_string(max_payload_);
    return false;
  }
  return true;
}

bool FrameDecoder::feed(const uint8_t* data, std::size_t size, Sink& sink) {
  if (failed()) return false;
  while (size > 0) {
    if (buffer_.empty() && size >= kFrameHeaderSize_bytes) {
      // Fast path: a whole frame in the read, delivered without copying.
      if (!check_header(data)) return false;
      const std::size_t length = get_u16(data);
      if (size >= kFrameHeaderSize_bytes + length) {
        ++frames_;
        sink.on_frame(static_cast<Channel>(data[2]), data + kFrameHeaderSize_bytes, length);
        data += kFrameHeaderSize_bytes + length;
        size -= kFrameHeaderSize_bytes + length;
        continue;
      }
    }
    // A frame split across reads: collect the header, then the payload.
    if (buffer_.size() < kFrameHeaderSize_bytes) {
      const std::size_t take = std::min(size, kFrameHeaderSize_bytes - buffer_.size());
      buffer_.insert(buffer_.end(), data, data + take);
      data += take;
      size -= take;
      if (buffer_.size() < kFrameHeaderSize_bytes) break;
      if (!check_header(buffer_.data())) {
        buffer_.clear();
        return false;
      }
    }
    const std::size_t want = kFrameHeaderSize_bytes + get_u16(buffer_.data());
    const std::size_t take = std::min(size, want - buffer_.size());
    buffer_.insert(buffer_.end(), data, data + take);
    data += take;
    size -= take;
    if (buffer_.size() == want) {
      ++frames_;
      sink.on_frame(static_cast<Channel>(buffer_[2]), buffer_.data() + kFrameHeaderSize_bytes, want - kFrameHeaderSize_bytes);
      buffer_.clear();
    }
  }
  return true;
}

}  // namespace hitl::adb
