// MAVLink 2 message signing: signature = first 6 bytes of
// SHA-256(secret_key (32) | header (10, from STX) | payload | checksum (2) | link id (1) | timestamp (6)).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "base/common/expected.h"

namespace hitl::mavlink {

using SigningKey = std::array<uint8_t, 32>;

/// A key from 64 hex digits, or the SHA-256 of a passphrase (as MAVProxy's `signing setup`).
Expected<SigningKey> parse_signing_key(std::string_view text);

/// The 6 signature bytes for a frame whose bytes up to and including the checksum are `signed_part`.
std::array<uint8_t, 6> compute_signature(const SigningKey& key, std::span<const uint8_t> signed_part, uint8_t link_id,
                                         uint64_t timestamp_10us);

/// Signature timestamp for now: 10 us units since 2015-01-01 00:00:00 UTC.
uint64_t signing_timestamp_now();

}  // namespace hitl::mavlink
