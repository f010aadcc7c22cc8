// What the flight stack tells the operator (STATUSTEXT): the emulator's mode changes, landings,
// auto-disarms and denials, with the severity PX4 gives them.
#pragma once

#include <string>

#include "base/common/severity.h"

namespace hitl::flight {

struct StatusMessage {
  Severity severity = Severity::Info;  ///< base/common/severity.h (a denial is Error: CRITICAL on the wire)
  std::string text;
};

}  // namespace hitl::flight
