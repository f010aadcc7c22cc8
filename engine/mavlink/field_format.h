// Decoded fields for people and scripts: text and JSON from any described message.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "base/mavlink/frame.h"
#include "base/mavlink/message_desc.h"

namespace hitl::mavlink {

/// One field's value as text: numbers, "[a, b]" for arrays, a quoted string for char arrays.
std::string format_field(const FieldDesc& field, const uint8_t* payload);

/// A field's value in words where a layer above knows them (PX4's custom_mode); nullopt: the usual text.
using FieldNamer = std::function<std::optional<std::string>(const Frame&, const FieldDesc&)>;

/// "NAME field=value field=value ..." on one line, with units, enum and bitmask values by name
/// (enum_names.h: type=QUADROTOR, base_mode=CUSTOM_MODE_ENABLED|SAFETY_ARMED), and words for
/// HIL_SENSOR.fields_updated. `namer`, when given, is asked first for each field.
std::string format_message(const Frame& frame, const FieldNamer& namer = {});

/// The frame's fields as a JSON object (char arrays as strings, other arrays as lists).
nlohmann::json fields_to_json(const Frame& frame);

}  // namespace hitl::mavlink
