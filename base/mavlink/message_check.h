// What checking a frame needs of its message, for every message of the official XML (minimal,
// standard, common, development), typed in messages.h or not: CRC_EXTRA, the payload lengths and
// where the target fields are, as mavgen's mavlink_msg_entry_t gives them to mavlink-router. The
// table (msg::kStandardChecks) is generated with the typed messages by tools/gen_messages.py; so a
// frame of any standard id has its checksum checked, and only ids outside the XML stay unverifiable.
#pragma once

#include <cstdint>

namespace hitl::mavlink {

struct MessageCheck {
  static constexpr uint8_t kHasTargetSystem = 0x01;
  static constexpr uint8_t kHasTargetComponent = 0x02;

  uint32_t id = 0;
  uint8_t crc_extra = 0;
  uint8_t min_length = 0;  ///< payload bytes without extensions (a MAVLink 1 frame's length)
  uint8_t max_length = 0;  ///< payload bytes with extensions
  uint8_t flags = 0;       ///< kHasTargetSystem | kHasTargetComponent
  uint8_t target_system_offset = 0;     ///< of target_system (MANUAL_CONTROL: target), when flagged
  uint8_t target_component_offset = 0;  ///< of target_component, when flagged
};

/// The official XML's entry for `id`, or null for an id outside it.
const MessageCheck* find_standard_check(uint32_t id);

}  // namespace hitl::mavlink
