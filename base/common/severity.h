// How much an event matters to the operator, spelled once for every layer: the session's and the
// emulated board's events, the flight core's messages, the dashboard's log. Ordered, so the worst
// of several is `worse()` (drake's KeepMoreSevere). On the wire it is MAV_SEVERITY
// (base/mavlink/severity.h converts both ways). Standard library only.
#pragma once

#include <cstdint>

namespace hitl {

enum class Severity : uint8_t { Info, Notice, Warning, Error };

constexpr Severity worse(Severity a, Severity b) { return static_cast<uint8_t>(a) >= static_cast<uint8_t>(b) ? a : b; }

constexpr const char* to_string(Severity severity) {
  switch (severity) {
    case Severity::Info: return "info";
    case Severity::Notice: return "notice";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "?";
}

}  // namespace hitl
