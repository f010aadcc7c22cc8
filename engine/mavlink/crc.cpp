#include "engine/mavlink/crc.h"

#include <array>

namespace hitl::mavlink {
namespace {

// Reflected polynomial 0x1021 -> 0x8408, one entry per low byte of (crc ^ data).
constexpr std::array<uint16_t, 256> make_table() {
  std::array<uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    uint16_t crc = static_cast<uint16_t>(i);
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1U) ? static_cast<uint16_t>((crc >> 1) ^ 0x8408U) : static_cast<uint16_t>(crc >> 1);
    table[i] = crc;
  }
  return table;
}

constexpr std::array<uint16_t, 256> kTable = make_table();

}  // namespace

uint16_t crc_accumulate(uint8_t byte, uint16_t crc) {
  return static_cast<uint16_t>((crc >> 8) ^ kTable[(crc ^ byte) & 0xFFU]);
}

uint16_t crc_x25(std::span<const uint8_t> data, uint16_t crc) {
  for (uint8_t byte : data) crc = static_cast<uint16_t>((crc >> 8) ^ kTable[(crc ^ byte) & 0xFFU]);
  return crc;
}

}  // namespace hitl::mavlink
