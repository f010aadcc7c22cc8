#include "base/mavlink/message_desc.h"

#include <algorithm>

#include "base/mavlink/crc.h"

namespace hitl::mavlink {

std::string_view to_string(FieldType type) {
  switch (type) {
    case FieldType::Char: return "char";
    case FieldType::Uint8: return "uint8_t";
    case FieldType::Int8: return "int8_t";
    case FieldType::Uint16: return "uint16_t";
    case FieldType::Int16: return "int16_t";
    case FieldType::Uint32: return "uint32_t";
    case FieldType::Int32: return "int32_t";
    case FieldType::Uint64: return "uint64_t";
    case FieldType::Int64: return "int64_t";
    case FieldType::Float: return "float";
    case FieldType::Double: return "double";
  }
  return "?";
}

uint8_t size_of(FieldType type) {
  switch (type) {
    case FieldType::Char:
    case FieldType::Uint8:
    case FieldType::Int8: return 1;
    case FieldType::Uint16:
    case FieldType::Int16: return 2;
    case FieldType::Uint32:
    case FieldType::Int32:
    case FieldType::Float: return 4;
    case FieldType::Uint64:
    case FieldType::Int64:
    case FieldType::Double: return 8;
  }
  return 1;
}

const FieldDesc* MessageDesc::field(std::string_view field_name) const {
  for (const auto& f : fields)
    if (f.name == field_name) return &f;
  return nullptr;
}

void assign_wire_order(MessageDesc& desc) {
  auto first_ext = std::stable_partition(desc.fields.begin(), desc.fields.end(), [](const FieldDesc& f) { return !f.extension; });
  std::stable_sort(desc.fields.begin(), first_ext, [](const FieldDesc& a, const FieldDesc& b) { return size_of(a.type) > size_of(b.type); });
  uint16_t offset = 0;
  uint16_t base = 0;
  for (auto& f : desc.fields) {
    f.offset = offset;
    offset = static_cast<uint16_t>(offset + f.wire_size());
    if (!f.extension) base = offset;
  }
  desc.min_length = static_cast<uint8_t>(std::min<uint16_t>(base, 255));
  desc.max_length = static_cast<uint8_t>(std::min<uint16_t>(offset, 255));
}

uint8_t compute_crc_extra(const MessageDesc& desc) {
  auto add = [](std::string_view text, uint16_t crc) {
    crc = crc_x25({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, crc);
    return crc_accumulate(' ', crc);
  };
  uint16_t crc = add(desc.name, kX25Init);
  for (const auto& f : desc.fields) {
    if (f.extension) continue;
    crc = add(to_string(f.type), crc);
    crc = add(f.name, crc);
    if (f.array_length != 0) crc = crc_accumulate(f.array_length, crc);
  }
  return static_cast<uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

}  // namespace hitl::mavlink
