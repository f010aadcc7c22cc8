// SHA-256 (FIPS 180-4), for MAVLink 2 message signing.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace hitl::mavlink {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const uint8_t> data);
  std::array<uint8_t, 32> finish();

 private:
  void block(const uint8_t* chunk);
  std::array<uint32_t, 8> h_;
  std::array<uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  uint64_t total_bytes_ = 0;
};

}  // namespace hitl::mavlink
