#include "engine/mavlink/field_format.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string_view>

#include "base/mavlink/hil_sensor_fields.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/enum_names.h"

namespace hitl::mavlink {
namespace {

template <class T>
T load(const uint8_t* p) {
  return detail::load_le<T>(p);
}

std::string number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return buf;
}

std::string element(FieldType type, const uint8_t* p) {
  switch (type) {
    case FieldType::Char: return std::to_string(static_cast<int>(static_cast<char>(*p)));
    case FieldType::Uint8: return std::to_string(load<uint8_t>(p));
    case FieldType::Int8: return std::to_string(load<int8_t>(p));
    case FieldType::Uint16: return std::to_string(load<uint16_t>(p));
    case FieldType::Int16: return std::to_string(load<int16_t>(p));
    case FieldType::Uint32: return std::to_string(load<uint32_t>(p));
    case FieldType::Int32: return std::to_string(load<int32_t>(p));
    case FieldType::Uint64: return std::to_string(load<uint64_t>(p));
    case FieldType::Int64: return std::to_string(load<int64_t>(p));
    case FieldType::Float: return number(load<float>(p));
    case FieldType::Double: return number(load<double>(p));
  }
  return "?";
}

nlohmann::json element_json(FieldType type, const uint8_t* p) {
  auto real = [](double v) -> nlohmann::json { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  switch (type) {
    case FieldType::Char: return static_cast<int>(static_cast<char>(*p));
    case FieldType::Uint8: return load<uint8_t>(p);
    case FieldType::Int8: return load<int8_t>(p);
    case FieldType::Uint16: return load<uint16_t>(p);
    case FieldType::Int16: return load<int16_t>(p);
    case FieldType::Uint32: return load<uint32_t>(p);
    case FieldType::Int32: return load<int32_t>(p);
    case FieldType::Uint64: return load<uint64_t>(p);
    case FieldType::Int64: return load<int64_t>(p);
    case FieldType::Float: return real(load<float>(p));
    case FieldType::Double: return real(load<double>(p));
  }
  return nullptr;
}

/// A scalar integer field's value, for the enum names; nullopt for arrays and reals.
std::optional<uint64_t> integer_value(const FieldDesc& field, const uint8_t* payload) {
  if (field.array_length != 0) return std::nullopt;
  const uint8_t* p = payload + field.offset;
  switch (field.type) {
    case FieldType::Uint8: return load<uint8_t>(p);
    case FieldType::Uint16: return load<uint16_t>(p);
    case FieldType::Uint32: return load<uint32_t>(p);
    case FieldType::Uint64: return load<uint64_t>(p);
    case FieldType::Int8: return static_cast<uint64_t>(load<int8_t>(p));
    case FieldType::Int16: return static_cast<uint64_t>(load<int16_t>(p));
    case FieldType::Int32: return static_cast<uint64_t>(load<int32_t>(p));
    case FieldType::Int64: return static_cast<uint64_t>(load<int64_t>(p));
    case FieldType::Char:
    case FieldType::Float:
    case FieldType::Double: return std::nullopt;
  }
  return std::nullopt;
}

/// The field's value by name when it takes values from an enum hitl names.
std::optional<std::string> enum_text(const FieldDesc& field, const uint8_t* payload) {
  if (field.enum_name.empty()) return std::nullopt;
  const auto value = integer_value(field, payload);
  if (!value) return std::nullopt;
  return enum_value_name(field.enum_name, *value);
}

std::string char_array(const FieldDesc& field, const uint8_t* payload) {
  const char* text = reinterpret_cast<const char*>(payload + field.offset);
  std::size_t n = 0;
  while (n < field.array_length && text[n] != '\0') ++n;
  return std::string(text, n);
}

}  // namespace

std::string format_field(const FieldDesc& field, const uint8_t* payload) {
  if (field.type == FieldType::Char && field.array_length > 0) {
    std::string out = "\"";
    for (char c : char_array(field, payload)) {
      if (c == '"' || c == '\\') out += '\\';
      if (static_cast<unsigned char>(c) < 0x20) {
        char esc[8];
        std::snprintf(esc, sizeof esc, "\\x%02x", static_cast<unsigned char>(c));
        out += esc;
      } else {
        out += c;
      }
    }
    return out + "\"";
  }
  const uint8_t* p = payload + field.offset;
  if (field.array_length == 0) return element(field.type, p);
  std::string out = "[";
  for (uint8_t i = 0; i < field.array_length; ++i) {
    if (i) out += ", ";
    out += element(field.type, p + i * size_of(field.type));
  }
  return out + "]";
}

std::string format_message(const Frame& frame, const FieldNamer& namer) {
  if (frame.desc == nullptr) return "#" + std::to_string(frame.msgid) + " (unknown id, " + std::to_string(frame.payload_len) + " bytes)";
  std::string out = frame.desc->name;
  for (const auto& f : frame.desc->fields) {
    out += ' ';
    out += f.name;
    out += '=';
    std::optional<std::string> named = namer ? namer(frame, f) : std::nullopt;
    if (!named) named = enum_text(f, frame.payload.data());
    out += named ? *named : format_field(f, frame.payload.data());
    if (!f.units.empty()) out += f.units == "%" ? "%" : " " + f.units;
    if (frame.msgid == msg::HilSensor::kId && f.name == "fields_updated") {
      const auto bits = detail::load_le<uint32_t>(frame.payload.data() + f.offset);
      out += " (" + hil_sensor::describe_fields_updated(bits) + ")";
    }
  }
  return out;
}

nlohmann::json fields_to_json(const Frame& frame) {
  nlohmann::json out = nlohmann::json::object();
  if (frame.desc == nullptr) return out;
  for (const auto& f : frame.desc->fields) {
    const uint8_t* p = frame.payload.data() + f.offset;
    if (f.type == FieldType::Char && f.array_length > 0) {
      out[f.name] = char_array(f, frame.payload.data());
    } else if (f.array_length > 0) {
      nlohmann::json arr = nlohmann::json::array();
      for (uint8_t i = 0; i < f.array_length; ++i) arr.push_back(element_json(f.type, p + i * size_of(f.type)));
      out[f.name] = std::move(arr);
    } else {
      out[f.name] = element_json(f.type, p);
    }
  }
  return out;
}

}  // namespace hitl::mavlink
