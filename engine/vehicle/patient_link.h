// Connecting to an autopilot that may not be there yet (a dashboard starts with its session, and
// the board answers once the simulator runs): retries VehicleLink::connect until it succeeds or
// `stop` turns true, saying each time why it is still waiting.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

/// The link, or null once `stop` turned true. `waiting` gets the reason of each failed attempt.
std::unique_ptr<VehicleLink> connect_patiently(const LinkOptions& options, const std::atomic<bool>& stop,
                                               const std::function<void(const std::string&)>& waiting);

/// Link options for a client of a running session or bridge on 127.0.0.1:`port`, from an
/// ephemeral local port (each dashboard thread has its own socket), discovery in `timeout_s`.
LinkOptions session_client_options(uint16_t port, double timeout_s = 2.0);

}  // namespace hitl::vehicle
