// Run-time description of a MAVLink message: what the parser, printer and
// dialect loader work from, for compiled-in and XML-loaded messages alike.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/mavlink/field_ref.h"

namespace hitl::mavlink {

struct FieldDesc {
  std::string name;
  FieldType type = FieldType::Uint8;
  uint8_t array_length = 0;  ///< 0 for a scalar
  uint16_t offset = 0;       ///< byte offset in the payload (wire order)
  bool extension = false;
  std::string units;         ///< as the XML gives it ("m/s/s", "degE7"), may be empty
  std::string enum_name;     ///< the XML enum this field takes values from, may be empty

  uint16_t wire_size() const { return static_cast<uint16_t>(size_of(type) * (array_length == 0 ? 1 : array_length)); }
};

struct MessageDesc {
  uint32_t id = 0;
  std::string name;
  uint8_t crc_extra = 0;
  uint8_t min_length = 0;  ///< payload bytes without extensions (a MAVLink 1 frame's length)
  uint8_t max_length = 0;  ///< payload bytes with extensions
  std::vector<FieldDesc> fields;  ///< wire order

  const FieldDesc* field(std::string_view field_name) const;
};

/// Sorts fields into wire order (base fields by element size, largest first, stable;
/// extensions after them in definition order) and fills offsets and lengths.
void assign_wire_order(MessageDesc& desc);

/// CRC_EXTRA from the message name and its base fields in wire order, as mavgen computes it.
uint8_t compute_crc_extra(const MessageDesc& desc);

}  // namespace hitl::mavlink
