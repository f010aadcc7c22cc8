// Compile-time field reflection for the typed MAVLink messages in messages.h.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <type_traits>

namespace hitl::mavlink {

/// Wire types of MAVLink fields, named as in the XML definitions.
enum class FieldType : uint8_t { Char, Uint8, Int8, Uint16, Int16, Uint32, Int32, Uint64, Int64, Float, Double };

/// The type's name as the XML (and so the CRC_EXTRA computation) spells it.
std::string_view to_string(FieldType type);
/// Bytes of one element of this type on the wire.
uint8_t size_of(FieldType type);

template <class T>
struct WireTypeOf;
template <> struct WireTypeOf<char> { static constexpr FieldType value = FieldType::Char; };
template <> struct WireTypeOf<uint8_t> { static constexpr FieldType value = FieldType::Uint8; };
template <> struct WireTypeOf<int8_t> { static constexpr FieldType value = FieldType::Int8; };
template <> struct WireTypeOf<uint16_t> { static constexpr FieldType value = FieldType::Uint16; };
template <> struct WireTypeOf<int16_t> { static constexpr FieldType value = FieldType::Int16; };
template <> struct WireTypeOf<uint32_t> { static constexpr FieldType value = FieldType::Uint32; };
template <> struct WireTypeOf<int32_t> { static constexpr FieldType value = FieldType::Int32; };
template <> struct WireTypeOf<uint64_t> { static constexpr FieldType value = FieldType::Uint64; };
template <> struct WireTypeOf<int64_t> { static constexpr FieldType value = FieldType::Int64; };
template <> struct WireTypeOf<float> { static constexpr FieldType value = FieldType::Float; };
template <> struct WireTypeOf<double> { static constexpr FieldType value = FieldType::Double; };

/// Element type and count of a member: scalars have array_length 0.
template <class T>
struct FieldShape {
  using Element = T;
  static constexpr uint8_t array_length = 0;
};
template <class T, std::size_t N>
struct FieldShape<std::array<T, N>> {
  using Element = T;
  static constexpr uint8_t array_length = N;
};

/// One field of a typed message: its name, member, unit and whether it is an extension.
template <class Message, class Member>
struct FieldRef {
  std::string_view name;
  Member Message::*member;
  std::string_view units;
  std::string_view enum_name;
  bool extension;

  using Element = typename FieldShape<Member>::Element;
  static constexpr FieldType type = WireTypeOf<Element>::value;
  static constexpr uint8_t array_length = FieldShape<Member>::array_length;
  static constexpr std::size_t wire_size = sizeof(Element) * (array_length == 0 ? 1 : array_length);
};

// Explicit guide: clang < 17 does not deduce template arguments for aggregates (P1816) on its own.
template <class Message, class Member>
FieldRef(std::string_view, Member Message::*, std::string_view, std::string_view, bool) -> FieldRef<Message, Member>;

template <class... Ts>
struct TypeList {};

}  // namespace hitl::mavlink
