#include "engine/net/link.h"

namespace hitl::net {

std::size_t Link::drain(mavlink::FrameParser& parser, const mavlink::FrameParser::FrameHandler& on_frame,
                        std::size_t max_reads) {
  return read_some(max_reads, [&](const LinkChunk& chunk) {
    if (chunk.whole_datagram) parser.parse_datagram(chunk.bytes, on_frame);
    else parser.feed(chunk.bytes, on_frame);
  });
}

}  // namespace hitl::net
