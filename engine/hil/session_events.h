// What the session and its parts say while they run: events in words with a severity, to an
// observer (the CLI prints them, the dashboard logs them). The engine never prints.
#pragma once

#include <optional>
#include <string>

#include "base/common/severity.h"
#include "engine/faults/fault_schedule.h"

namespace hitl::hil {

using Severity = ::hitl::Severity;  // base/common/severity.h

struct SessionEvent {
  Severity severity = Severity::Info;
  std::string text;
  std::optional<faults::FaultChange> fault;  ///< a fault started or ended (text says it too)
};

class EventSink {
 public:
  virtual ~EventSink() = default;
  virtual void on_event(const SessionEvent& /*event*/) {}
};

}  // namespace hitl::hil
