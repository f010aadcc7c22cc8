// Payload packing for the typed messages of messages.h, little-endian in wire order.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <tuple>

#include "base/mavlink/message_desc.h"

namespace hitl::mavlink {
namespace detail {

template <class T>
inline void store_le(uint8_t* out, T value) {
  std::memcpy(out, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(out, out + sizeof(T));
}

template <class T>
inline T load_le(const uint8_t* in) {
  T value;
  if constexpr (std::endian::native == std::endian::big) {
    uint8_t tmp[sizeof(T)];
    std::reverse_copy(in, in + sizeof(T), tmp);
    std::memcpy(&value, tmp, sizeof(T));
  } else {
    std::memcpy(&value, in, sizeof(T));
  }
  return value;
}

template <class T>
inline void put(uint8_t*& out, const T& value) {
  store_le(out, value);
  out += sizeof(T);
}
template <class T, std::size_t N>
inline void put(uint8_t*& out, const std::array<T, N>& values) {
  for (const T& v : values) put(out, v);
}
template <class T>
inline void get(const uint8_t*& in, T& value) {
  value = load_le<T>(in);
  in += sizeof(T);
}
template <class T, std::size_t N>
inline void get(const uint8_t*& in, std::array<T, N>& values) {
  for (T& v : values) get(in, v);
}

}  // namespace detail

/// Writes all M::kMaxLength payload bytes of `message` to `out` (untruncated).
template <class M>
void encode_payload(const M& message, uint8_t* out) {
  static constexpr auto kFields = M::fields();  // a constant: the member pointers fold away
  std::apply([&](const auto&... field) { (detail::put(out, message.*(field.member)), ...); }, kFields);
}

/// Reads a message from a payload zero-extended to at least M::kMaxLength bytes.
template <class M>
M decode_payload(const uint8_t* payload) {
  M message;
  static constexpr auto kFields = M::fields();
  std::apply([&](const auto&... field) { (detail::get(payload, message.*(field.member)), ...); }, kFields);
  return message;
}

/// The run-time description of a typed message.
template <class M>
MessageDesc describe() {
  MessageDesc desc;
  desc.id = M::kId;
  desc.name = std::string(M::kName);
  desc.crc_extra = M::kCrcExtra;
  std::apply(
      [&](const auto&... field) {
        (desc.fields.push_back(FieldDesc{std::string(field.name), field.type, field.array_length, 0, field.extension,
                                         std::string(field.units), std::string(field.enum_name)}),
         ...);
      },
      M::fields());
  uint16_t offset = 0;
  for (auto& f : desc.fields) {
    f.offset = offset;
    offset = static_cast<uint16_t>(offset + f.wire_size());
  }
  desc.min_length = M::kMinLength;
  desc.max_length = M::kMaxLength;
  return desc;
}

}  // namespace hitl::mavlink
