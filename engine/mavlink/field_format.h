// Decoded fields for people and scripts: text and JSON from any described message.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>

#include "engine/mavlink/frame.h"
#include "engine/mavlink/message_desc.h"

namespace hitl::mavlink {

/// One field's value as text: numbers, "[a, b]" for arrays, a quoted string for char arrays.
std::string format_field(const FieldDesc& field, const uint8_t* payload);

/// "NAME field=value field=value ..." with units, and words for HIL_SENSOR.fields_updated.
std::string format_message(const Frame& frame);

/// The frame's fields as a JSON object (char arrays as strings, other arrays as lists).
nlohmann::json fields_to_json(const Frame& frame);

}  // namespace hitl::mavlink
