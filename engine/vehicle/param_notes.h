// Parameters of the spec's HITL set that a firmware does not have, and what replaces them there:
// the "#absent NAME | FIRMWARE | WHAT REPLACES IT" lines of base/contract/hitl-defaults.params.
// `hitl params check/diff/reset` report such a parameter as absent rather than wrong.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace hitl::vehicle {

struct AbsentParamNote {
  std::string name;         ///< COM_ARM_EKF_POS
  std::string firmware;     ///< the firmware known to lack it: "PX4 v1.16"
  std::string replacement;  ///< what replaces it there, in words
};

/// The "#absent" lines of a .params text; malformed ones (fewer than three fields) are skipped.
std::vector<AbsentParamNote> parse_absent_notes(std::string_view text);
/// Those of the compiled-in HITL set.
const std::vector<AbsentParamNote>& hitl_absent_notes();
/// The note for `name`, or nullptr.
const AbsentParamNote* find_absent_note(const std::string& name);

}  // namespace hitl::vehicle
