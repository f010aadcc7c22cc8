// MAV_SEVERITY (STATUSTEXT.severity, 8 levels) <-> hitl's Severity (base/common/severity.h, 4).
#pragma once

#include <cstdint>

#include "base/common/severity.h"
#include "base/mavlink/enums.h"

namespace hitl::mavlink {

/// EMERGENCY..ERROR -> Error, WARNING -> Warning, NOTICE -> Notice, INFO and DEBUG -> Info.
constexpr Severity severity_of(uint8_t mav_severity) {
  if (mav_severity <= static_cast<uint8_t>(MavSeverity::Error)) return Severity::Error;
  if (mav_severity == static_cast<uint8_t>(MavSeverity::Warning)) return Severity::Warning;
  if (mav_severity == static_cast<uint8_t>(MavSeverity::Notice)) return Severity::Notice;
  return Severity::Info;
}

/// What a STATUSTEXT carries for it; Error goes out as CRITICAL, as PX4's commander sends a denial.
constexpr MavSeverity mav_severity(Severity severity) {
  switch (severity) {
    case Severity::Info: return MavSeverity::Info;
    case Severity::Notice: return MavSeverity::Notice;
    case Severity::Warning: return MavSeverity::Warning;
    case Severity::Error: return MavSeverity::Critical;
  }
  return MavSeverity::Info;
}

}  // namespace hitl::mavlink
