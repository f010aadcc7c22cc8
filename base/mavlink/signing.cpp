#include "base/mavlink/signing.h"

#include <chrono>
#include <string>

#include "base/mavlink/sha256.h"

namespace hitl::mavlink {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// 2015-01-01 00:00:00 UTC in seconds since the Unix epoch.
constexpr int64_t kSigningEpochUnix_s = 1420070400;

}  // namespace

Expected<SigningKey> parse_signing_key(std::string_view text) {
  if (text.empty()) return Error::input("the signing key is empty");
  SigningKey key{};
  bool hex = text.size() == 64;
  for (std::size_t i = 0; hex && i < 32; ++i) {
    const int hi = hex_value(text[2 * i]);
    const int lo = hex_value(text[2 * i + 1]);
    if (hi < 0 || lo < 0) hex = false;
    else key[i] = static_cast<uint8_t>(hi * 16 + lo);
  }
  if (hex) return key;
  Sha256 sha;
  sha.update({reinterpret_cast<const uint8_t*>(text.data()), text.size()});
  return sha.finish();
}

std::array<uint8_t, 6> compute_signature(const SigningKey& key, std::span<const uint8_t> signed_part, uint8_t link_id,
                                         uint64_t timestamp_10us) {
  Sha256 sha;
  sha.update(key);
  sha.update(signed_part);
  uint8_t tail[7];
  tail[0] = link_id;
  for (int i = 0; i < 6; ++i) tail[1 + i] = static_cast<uint8_t>(timestamp_10us >> (8 * i));
  sha.update({tail, 7});
  const auto digest = sha.finish();
  std::array<uint8_t, 6> sig{};
  for (std::size_t i = 0; i < 6; ++i) sig[i] = digest[i];
  return sig;
}

uint64_t signing_timestamp_now() {
  const auto now_us = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  return static_cast<uint64_t>((now_us - kSigningEpochUnix_s * 1000000) / 10);
}

}  // namespace hitl::mavlink
