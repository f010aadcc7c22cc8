#include "base/mavlink/frame_encoder.h"

#include <algorithm>
#include <cstring>

#include "base/mavlink/crc.h"

namespace hitl::mavlink {

FrameEncoder::FrameEncoder(uint8_t sysid, uint8_t compid, Version version)
    : sysid_(sysid), compid_(compid), version_(version) {}

void FrameEncoder::set_signing(const SigningKey& key, uint8_t link_id) { signer_ = Signer{key, link_id, 0}; }

std::size_t truncated_length(std::span<const uint8_t> payload) {
  std::size_t len = payload.size();
  while (len > 1 && payload[len - 1] == 0) --len;
  return len;
}

std::size_t FrameEncoder::encode_raw(uint32_t msgid, uint8_t crc_extra, std::span<const uint8_t> payload,
                                     uint8_t min_length, FrameBuffer& out) {
  std::size_t pos = 0;
  std::size_t len = 0;
  if (version_ == Version::V1) {
    if (msgid > 255) return 0;
    len = std::min<std::size_t>(min_length, payload.size());
    out[0] = kStxV1;
    out[1] = static_cast<uint8_t>(len);
    out[2] = seq_;
    out[3] = sysid_;
    out[4] = compid_;
    out[5] = static_cast<uint8_t>(msgid);
    pos = kHeaderLenV1;
  } else {
    len = truncated_length(payload.first(std::min(payload.size(), kMaxPayloadLen)));
    out[0] = kStxV2;
    out[1] = static_cast<uint8_t>(len);
    out[2] = signer_ ? kIncompatFlagSigned : 0;
    out[3] = 0;
    out[4] = seq_;
    out[5] = sysid_;
    out[6] = compid_;
    out[7] = static_cast<uint8_t>(msgid);
    out[8] = static_cast<uint8_t>(msgid >> 8);
    out[9] = static_cast<uint8_t>(msgid >> 16);
    pos = kHeaderLenV2;
  }
  std::memcpy(out.data() + pos, payload.data(), len);
  pos += len;
  uint16_t crc = crc_x25(std::span<const uint8_t>(out.data() + 1, pos - 1));
  crc = crc_accumulate(crc_extra, crc);
  out[pos++] = static_cast<uint8_t>(crc);
  out[pos++] = static_cast<uint8_t>(crc >> 8);
  if (version_ == Version::V2 && signer_) {
    const uint64_t now = signing_timestamp_now();
    signer_->last_timestamp_10us = std::max(now, signer_->last_timestamp_10us + 1);
    const uint64_t ts = signer_->last_timestamp_10us;
    const auto sig = compute_signature(signer_->key, std::span<const uint8_t>(out.data(), pos), signer_->link_id, ts);
    out[pos++] = signer_->link_id;
    for (int i = 0; i < 6; ++i) out[pos++] = static_cast<uint8_t>(ts >> (8 * i));
    for (uint8_t b : sig) out[pos++] = b;
  }
  ++seq_;
  return pos;
}

}  // namespace hitl::mavlink
