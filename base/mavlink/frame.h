// A MAVLink frame as it travels: header, payload, checksum, optional signature.
//
// v2 frame (bytes): STX 0xFD | len | incompat | compat | seq | sysid | compid | msgid (3, LE)
//                   | payload (len) | checksum (2, LE) | signature (13, when incompat & 0x01)
//                   = 10 + len + 2 [+ 13]
// v1 frame (bytes): STX 0xFE | len | seq | sysid | compid | msgid (1) | payload | checksum (2)
//                   = 6 + len + 2
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "base/mavlink/message_check.h"
#include "base/mavlink/message_desc.h"
#include "base/mavlink/typed_codec.h"

namespace hitl::mavlink {

inline constexpr uint8_t kStxV1 = 0xFE;
inline constexpr uint8_t kStxV2 = 0xFD;
inline constexpr uint8_t kIncompatFlagSigned = 0x01;
inline constexpr std::size_t kHeaderLenV1 = 6;   ///< including STX
inline constexpr std::size_t kHeaderLenV2 = 10;  ///< including STX
inline constexpr std::size_t kChecksumLen = 2;
inline constexpr std::size_t kSignatureLen = 13;  ///< link id (1) + timestamp (6) + signature (6)
inline constexpr std::size_t kMaxPayloadLen = 255;
inline constexpr std::size_t kMaxFrameLen = kHeaderLenV2 + kMaxPayloadLen + kChecksumLen + kSignatureLen;  // 280

enum class Version : uint8_t { V1 = 1, V2 = 2 };

struct Frame {
  Version version = Version::V2;
  uint8_t incompat_flags = 0;
  uint8_t compat_flags = 0;
  uint8_t seq = 0;
  uint8_t sysid = 0;
  uint8_t compid = 0;
  uint32_t msgid = 0;
  uint8_t payload_len = 0;                       ///< bytes on the wire (v2 may be truncated)
  std::array<uint8_t, kMaxPayloadLen> payload{};  ///< zero-extended past payload_len
  uint16_t checksum = 0;
  std::array<uint8_t, kSignatureLen> signature{};  ///< valid when is_signed()
  std::array<uint8_t, kMaxFrameLen> raw{};         ///< the frame's bytes as received or sent
  uint16_t raw_len = 0;
  const MessageDesc* desc = nullptr;  ///< null for an id the message set does not know
  const MessageCheck* check = nullptr;  ///< the official XML's entry (CRC checked, target offsets); null outside it

  bool is_signed() const { return (incompat_flags & kIncompatFlagSigned) != 0; }
  std::span<const uint8_t> bytes() const { return {raw.data(), raw_len}; }
  uint8_t signature_link_id() const { return signature[0]; }
  /// 48-bit signature timestamp: units of 10 us since 2015-01-01 00:00:00 UTC.
  uint64_t signature_timestamp() const {
    uint64_t t = 0;
    for (int i = 6; i >= 1; --i) t = (t << 8) | signature[static_cast<std::size_t>(i)];
    return t;
  }

  template <class M>
  bool is() const { return msgid == M::kId; }
  /// Decodes the payload as M; check is<M>() first.
  template <class M>
  M as() const { return decode_payload<M>(payload.data()); }
};

}  // namespace hitl::mavlink
