#include "base/mavlink/crc.h"

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

// Slicing-by-8: kSlice[k][i] is the checksum change of byte i followed by k zero bytes, so eight
// bytes fold in with eight independent lookups instead of a chain of eight dependent ones.
constexpr std::array<std::array<uint16_t, 256>, 8> make_slices() {
  std::array<std::array<uint16_t, 256>, 8> t{};
  t[0] = make_table();
  for (std::size_t k = 1; k < 8; ++k)
    for (unsigned i = 0; i < 256; ++i) t[k][i] = static_cast<uint16_t>((t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFFU]);
  return t;
}

constexpr auto kSlice = make_slices();

}  // namespace

uint16_t crc_accumulate(uint8_t byte, uint16_t crc) {
  return static_cast<uint16_t>((crc >> 8) ^ kTable[(crc ^ byte) & 0xFFU]);
}

uint16_t crc_x25(std::span<const uint8_t> data, uint16_t crc) {
  const uint8_t* p = data.data();
  std::size_t n = data.size();
  for (; n >= 8; p += 8, n -= 8) {
    crc = static_cast<uint16_t>(kSlice[7][(p[0] ^ crc) & 0xFFU] ^ kSlice[6][p[1] ^ (crc >> 8)] ^ kSlice[5][p[2]] ^
                                kSlice[4][p[3]] ^ kSlice[3][p[4]] ^ kSlice[2][p[5]] ^ kSlice[1][p[6]] ^ kSlice[0][p[7]]);
  }
  for (; n > 0; ++p, --n) crc = static_cast<uint16_t>((crc >> 8) ^ kTable[(crc ^ *p) & 0xFFU]);
  return crc;
}

}  // namespace hitl::mavlink
