// Listening to a running session's client port on its own, when doctor's link to the autopilot
// does not go through it (--connect udp:..., or no autopilot answered): the session's status
// (HEARTBEAT and NAMED_VALUE_* from the simulator, engine/hil/session_config.h) reaches every client.
#pragma once

#include <cstdint>
#include <functional>

#include "base/mavlink/frame.h"

namespace hitl::doctor {

/// Sends a ground station's HEARTBEAT to 127.0.0.1:`port` each second (the session then counts this
/// socket as a client) and hands every frame heard within `listen_s` to `on_frame` with its
/// monotonic time. Returns at once when no socket holds the port (net::udp_port_in_use); the link
/// is engine/net's (udp:127.0.0.1:PORT, hearing the session only).
void probe_session(uint16_t port, double listen_s, const std::function<void(const mavlink::Frame&, double)>& on_frame);

}  // namespace hitl::doctor
