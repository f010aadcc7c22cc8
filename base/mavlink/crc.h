// X.25 CRC-16 (CRC-16/MCRF4XX) as MAVLink computes its frame checksum.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace hitl::mavlink {

inline constexpr uint16_t kX25Init = 0xFFFF;

/// Adds one byte to a running checksum.
uint16_t crc_accumulate(uint8_t byte, uint16_t crc);
/// Adds bytes to a running checksum (table driven).
uint16_t crc_x25(std::span<const uint8_t> data, uint16_t crc = kX25Init);

}  // namespace hitl::mavlink
