#include "engine/net/link.h"

#include <algorithm>

namespace hitl::net {

std::size_t Link::drain(mavlink::FrameParser& parser, const mavlink::FrameParser::FrameHandler& on_frame,
                        std::size_t max_reads) {
  return read_some(max_reads, [&](const LinkChunk& chunk) {
    if (chunk.whole_datagram) parser.parse_datagram(chunk.bytes, on_frame);
    else parser.feed(chunk.bytes, on_frame);
  });
}

std::size_t Link::drain_from(mavlink::FrameParser& parser, const SourcedFrameHandler& on_frame, std::size_t max_reads) {
  return read_some(max_reads, [&](const LinkChunk& chunk) {
    const auto handler = [&](const mavlink::Frame& f) { on_frame(f, chunk.from); };
    if (chunk.whole_datagram) parser.parse_datagram(chunk.bytes, handler);
    else parser.feed(chunk.bytes, handler);
  });
}

Status Link::send_to_peers(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except,
                           std::span<const SocketAddress> only) {
  const auto to = peer();
  if (except && to && *to == *except) return Ok{};
  if (!only.empty() && (!to || std::find(only.begin(), only.end(), *to) == only.end())) return Ok{};
  return send(bytes);
}

}  // namespace hitl::net
