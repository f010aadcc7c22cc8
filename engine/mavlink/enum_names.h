// Names for the enum and bitmask values hitl knows (enums.h), as the dialect spells them without
// the enum's prefix: HEARTBEAT type=QUADROTOR, base_mode=CUSTOM_MODE_ENABLED|SAFETY_ARMED,
// COMMAND_ACK result=DENIED, STATUSTEXT severity=WARNING. Values enums.h does not hold stay numbers.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hitl::mavlink {

/// The value's name in `enum_name` (the XML enum a field names, FieldDesc::enum_name): "QUADROTOR"
/// for MAV_TYPE 2; for a bitmask enum the set bits joined by '|' ("CUSTOM_MODE_ENABLED|SAFETY_ARMED",
/// bits without a name as "0x400", no bit set as "0"). nullopt for an enum hitl has no names for, or
/// a value of a plain enum it has no name for.
std::optional<std::string> enum_value_name(std::string_view enum_name, uint64_t value);

}  // namespace hitl::mavlink
