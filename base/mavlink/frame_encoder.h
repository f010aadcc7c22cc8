// Serializes messages into MAVLink frames for one link: the sender's system and
// component ids, its own sequence numbers, v2 payload zero-truncation, optional signing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "base/mavlink/frame.h"
#include "base/mavlink/signing.h"
#include "base/mavlink/typed_codec.h"

namespace hitl::mavlink {

using FrameBuffer = std::array<uint8_t, kMaxFrameLen>;

struct Signer {
  SigningKey key{};
  uint8_t link_id = 0;
  uint64_t last_timestamp_10us = 0;  ///< each frame gets a later timestamp than the one before
};

class FrameEncoder {
 public:
  FrameEncoder(uint8_t sysid, uint8_t compid, Version version = Version::V2);

  /// Encodes `message` into `out`; returns the frame length (0 when the message cannot be sent as v1).
  template <class M>
  std::size_t encode(const M& message, FrameBuffer& out) {
    std::array<uint8_t, kMaxPayloadLen> payload{};
    encode_payload(message, payload.data());
    return encode_raw(M::kId, M::kCrcExtra, std::span<const uint8_t>(payload.data(), M::kMaxLength), M::kMinLength, out);
  }

  /// Encodes an already packed, untruncated payload (dialect-loaded messages, routers).
  std::size_t encode_raw(uint32_t msgid, uint8_t crc_extra, std::span<const uint8_t> payload, uint8_t min_length,
                         FrameBuffer& out);

  void set_signing(const SigningKey& key, uint8_t link_id);
  void set_version(Version version) { version_ = version; }
  uint8_t sysid() const { return sysid_; }
  uint8_t compid() const { return compid_; }
  uint8_t next_seq() const { return seq_; }

 private:
  uint8_t sysid_;
  uint8_t compid_;
  Version version_;
  uint8_t seq_ = 0;
  std::optional<Signer> signer_;
};

/// Length of a v2 payload after dropping trailing zero bytes (at least 1 byte is kept).
std::size_t truncated_length(std::span<const uint8_t> payload);

}  // namespace hitl::mavlink
