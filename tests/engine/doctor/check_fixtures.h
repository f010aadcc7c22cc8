// What several doctor check tests share: a text search for the words a result must carry, the
// HEARTBEAT PX4 sends, and the status a hitl sim session broadcasts.
#pragma once

#include <cstdint>
#include <string>

#include "engine/doctor/observations.h"

namespace hitl::doctor::fixtures {

inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

inline HeartbeatSeen px4_heartbeat(uint8_t base_mode) {
  HeartbeatSeen h;
  h.sysid = 1;
  h.autopilot = 12;
  h.base_mode = base_mode;
  h.custom_mode = 3u << 16;
  h.count = 3;
  h.first_s = 10;
  h.last_s = 12;
  return h;
}

inline SessionStatus session(bool lockstep, double rtf, double act_hz, int32_t flags, int32_t armed) {
  SessionStatus s;
  s.sysid = 250;
  s.reports = 2;
  s.rtf = rtf;
  s.speed = rtf;
  s.paused = false;
  s.lockstep = lockstep;
  s.actuator_hz = act_hz;
  s.actuator_flags = flags;
  s.actuator_armed = armed;
  return s;
}

}  // namespace hitl::doctor::fixtures
