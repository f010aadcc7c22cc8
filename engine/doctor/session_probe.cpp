#include "engine/doctor/session_probe.h"

#include <algorithm>

#include "base/common/clock.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/message_set.h"
#include "engine/net/open_link.h"

namespace hitl::doctor {

void probe_session(uint16_t port, double listen_s, const std::function<void(const mavlink::Frame&, double)>& on_frame) {
  net::LinkSpec spec;
  spec.kind = net::LinkSpec::Kind::Udp;
  spec.host = "127.0.0.1";
  spec.port = port;
  spec.text = spec.to_string();
  // Nothing holds the port: no session. Asked by binding it, not by sending to it: a datagram would
  // make the session count one more client.
  if (auto held = net::udp_port_in_use(port); held && !*held) return;
  net::LinkSettings settings;
  settings.name = "the session port";
  settings.hear_peer_only = true;  // the session answers from its client port; anything else is not it
  auto link = net::open_link(spec, settings);
  if (!link) return;
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  mavlink::FrameEncoder encoder(mavlink::kGcsSystemId, mavlink::kCompIdMissionPlanner);
  const double end_s = monotonic_s() + listen_s;
  double next_heartbeat_s = 0;
  for (;;) {
    const double now_s = monotonic_s();
    if (now_s >= end_s) break;
    if (now_s >= next_heartbeat_s) {
      next_heartbeat_s = now_s + 1.0;
      mavlink::FrameBuffer frame;
      const std::size_t n = encoder.encode(mavlink::gcs_heartbeat(), frame);
      (void)(*link)->send({frame.data(), n});
    }
    const double wait_s = std::min(end_s, next_heartbeat_s) - now_s;
    if (!(*link)->wait_readable(static_cast<int>(wait_s * 1000) + 1)) continue;
    (*link)->drain(parser, [&](const mavlink::Frame& f) { on_frame(f, monotonic_s()); });
  }
}

}  // namespace hitl::doctor
