#include "engine/ulog/ulog_format.h"

#include <array>
#include <cstring>
#include <utility>

namespace hitl::ulog {
namespace {

constexpr std::size_t kMaxLayoutBytes = std::size_t{1} << 20;  ///< a topic larger than this is no PX4 topic
constexpr std::size_t kMaxArrayLength = 65535;                  ///< a 'D' message holds at most 65533 bytes

constexpr std::array<std::pair<std::string_view, BasicType>, 12> kBasicTypes = {{
    {"int8_t", BasicType::Int8},
    {"uint8_t", BasicType::UInt8},
    {"int16_t", BasicType::Int16},
    {"uint16_t", BasicType::UInt16},
    {"int32_t", BasicType::Int32},
    {"uint32_t", BasicType::UInt32},
    {"int64_t", BasicType::Int64},
    {"uint64_t", BasicType::UInt64},
    {"float", BasicType::Float},
    {"double", BasicType::Double},
    {"bool", BasicType::Bool},
    {"char", BasicType::Char},
}};

bool name_char(char c, bool slash_dash) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         (slash_dash && (c == '/' || c == '-'));
}

bool valid_name(std::string_view s, bool slash_dash) {
  if (s.empty() || s.size() > 255) return false;
  for (char c : s)
    if (!name_char(c, slash_dash)) return false;
  return true;
}

/// "float[3]" -> ("float", 3, array); nullopt when the brackets or the length are wrong.
std::optional<FormatField> parse_type(std::string_view type) {
  FormatField f;
  const auto open = type.find('[');
  if (open == std::string_view::npos) {
    f.type = std::string(type);
  } else {
    if (type.back() != ']' || open + 2 > type.size() - 1) return std::nullopt;
    const std::string_view digits = type.substr(open + 1, type.size() - open - 2);
    if (digits.empty() || digits.size() > 5) return std::nullopt;
    std::size_t n = 0;
    for (char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      n = n * 10 + static_cast<std::size_t>(c - '0');
    }
    if (n == 0 || n > kMaxArrayLength) return std::nullopt;
    f.type = std::string(type.substr(0, open));
    f.count = n;
    f.array = true;
  }
  if (!valid_name(f.type, true)) return std::nullopt;
  return f;
}

template <class T>
double load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);  // fields are unaligned; the hosts hitl runs on are little endian, as ULog is
  return static_cast<double>(v);
}

}  // namespace

std::optional<BasicType> basic_type(std::string_view name) {
  for (const auto& [n, t] : kBasicTypes)
    if (n == name) return t;
  return std::nullopt;
}

std::size_t basic_size(BasicType type) {
  switch (type) {
    case BasicType::Int8:
    case BasicType::UInt8:
    case BasicType::Bool:
    case BasicType::Char: return 1;
    case BasicType::Int16:
    case BasicType::UInt16: return 2;
    case BasicType::Int32:
    case BasicType::UInt32:
    case BasicType::Float: return 4;
    case BasicType::Int64:
    case BasicType::UInt64:
    case BasicType::Double: return 8;
  }
  return 1;
}

std::optional<Format> parse_format(std::string_view text) {
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  Format format;
  format.name = std::string(text.substr(0, colon));
  if (!valid_name(format.name, true) || basic_type(format.name)) return std::nullopt;
  std::string_view rest = text.substr(colon + 1);
  while (!rest.empty()) {
    const auto semi = rest.find(';');
    const std::string_view item = rest.substr(0, semi);
    rest = semi == std::string_view::npos ? std::string_view{} : rest.substr(semi + 1);
    if (item.empty()) continue;
    const auto space = item.find(' ');
    if (space == std::string_view::npos) return std::nullopt;
    auto field = parse_type(item.substr(0, space));
    if (!field) return std::nullopt;
    field->name = std::string(item.substr(space + 1));
    if (!valid_name(field->name, false)) return std::nullopt;
    format.fields.push_back(std::move(*field));
  }
  if (format.fields.empty()) return std::nullopt;
  return format;
}

std::optional<std::size_t> Layouts::field_size(const FormatField& f, int depth) {
  std::size_t element = 0;
  if (auto b = basic_type(f.type)) {
    element = basic_size(*b);
  } else {
    auto nested = size_at(f.type, depth + 1);
    if (!nested) return std::nullopt;
    element = *nested;
  }
  if (element > kMaxLayoutBytes / f.count) return std::nullopt;  // no overflow: count <= 65535
  return element * f.count;
}

std::optional<std::size_t> Layouts::size_at(const std::string& name, int depth) {
  if (depth > max_nesting_) return std::nullopt;
  if (auto it = sizes_.find(name); it != sizes_.end()) return it->second;
  const auto format = formats_.find(name);
  if (format == formats_.end()) return std::nullopt;
  sizes_[name] = std::nullopt;  // a cycle back to this name finds it unusable
  std::size_t total = 0;
  for (const auto& f : format->second.fields) {
    auto s = field_size(f, depth);
    if (!s || total + *s > kMaxLayoutBytes) return std::nullopt;
    total += *s;
  }
  sizes_[name] = total;
  return total;
}

std::optional<FieldLocation> Layouts::locate(const std::string& topic, std::string_view field) {
  const auto format = formats_.find(topic);
  if (format == formats_.end()) return std::nullopt;
  std::size_t index = 0;
  bool indexed = false;
  if (const auto open = field.find('['); open != std::string_view::npos) {
    if (field.back() != ']' || open + 2 > field.size() - 1) return std::nullopt;
    const std::string_view digits = field.substr(open + 1, field.size() - open - 2);
    if (digits.size() > 5) return std::nullopt;
    for (char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      index = index * 10 + static_cast<std::size_t>(c - '0');
    }
    field = field.substr(0, open);
    indexed = true;
  }
  std::size_t offset = 0;
  for (const auto& f : format->second.fields) {
    if (f.name == field) {
      const auto b = basic_type(f.type);
      if (!b || index >= f.count || (indexed && !f.array)) return std::nullopt;
      return FieldLocation{*b, offset + index * basic_size(*b)};
    }
    auto s = field_size(f, 0);
    if (!s) return std::nullopt;
    offset += *s;
  }
  return std::nullopt;
}

double decode_basic(BasicType type, const uint8_t* p) {
  switch (type) {
    case BasicType::Int8: return load<int8_t>(p);
    case BasicType::UInt8:
    case BasicType::Char: return load<uint8_t>(p);
    case BasicType::Bool: return *p != 0 ? 1.0 : 0.0;
    case BasicType::Int16: return load<int16_t>(p);
    case BasicType::UInt16: return load<uint16_t>(p);
    case BasicType::Int32: return load<int32_t>(p);
    case BasicType::UInt32: return load<uint32_t>(p);
    case BasicType::Int64: return load<int64_t>(p);
    case BasicType::UInt64: return load<uint64_t>(p);
    case BasicType::Float: return load<float>(p);
    case BasicType::Double: return load<double>(p);
  }
  return 0;
}

}  // namespace hitl::ulog
