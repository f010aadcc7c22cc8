// The node-mavlink conformance test's cases: for every message and fill, hitl's frame (and, for the
// random fill, its signed frame), the untruncated payload, and the job node/check.js is given.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "base/mavlink/crc.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"
#include "tests/base/mavlink/node_mavlink_values.h"

namespace hitl::mavlink::conformance {

using json = nlohmann::json;

constexpr uint8_t kSysid = 7;
constexpr uint8_t kCompid = 200;
constexpr uint8_t kLinkId = 3;
constexpr uint64_t kSignEpochMs = 1420070400000ULL;      // 2015-01-01T00:00:00Z
constexpr uint64_t kSignBaseMs = 1700000000000ULL;       // a fixed signing time (ms since Unix epoch)
constexpr SigningKey kKey = {0x9a, 0x1c, 0x44, 0x07, 0xe2, 0x5d, 0x80, 0x31, 0x6f, 0xc4, 0x12, 0xab, 0x03, 0x99, 0x58, 0x21,
                             0xde, 0x70, 0x0b, 0x6a, 0x35, 0xf1, 0x8c, 0x27, 0x41, 0xb9, 0x5e, 0x02, 0xcd, 0x13, 0x76, 0xe8};

inline std::string to_hex(std::span<const uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (uint8_t b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0x0F];
  }
  return out;
}

struct Case {
  std::string name;      ///< "HIL_SENSOR/random"
  std::string msgname;
  Fill fill = Fill::Random;
  uint8_t seq = 0;
  std::vector<uint8_t> hitl_frame;
  std::vector<uint8_t> hitl_signed_frame;
  std::array<uint8_t, kMaxPayloadLen> payload{};  ///< untruncated payload of the values
  const MessageDesc* desc = nullptr;
  uint64_t sign_ms = 0;  ///< node signs at this time when non-zero
  /// hitl's decode of node-mavlink's frame, re-encoded untruncated (filled by the checker).
  std::function<std::array<uint8_t, kMaxPayloadLen>(const Frame&)> reencode;
};

template <class M>
void add_cases(std::vector<Case>& cases, json& jobs, FrameEncoder& encoder, FrameEncoder& signer, const MessageSet& set) {
  const MessageDesc* desc = set.find(M::kId);
  ASSERT_NE(desc, nullptr) << M::kName;
  for (Fill fill : {Fill::Random, Fill::Extremes, Fill::TrailingZero, Fill::AllZero}) {
    Case c;
    c.msgname = std::string(M::kName);
    c.name = c.msgname + "/" + fill_name(fill);
    c.fill = fill;
    c.desc = desc;
    const M message = make_message<M>(fill, (uint64_t{M::kId} << 8) ^ static_cast<uint64_t>(fill) ^ 0x5EED0000ULL);
    encode_payload(message, c.payload.data());
    c.seq = encoder.next_seq();
    FrameBuffer buf{};
    c.hitl_frame.assign(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(encoder.encode(message, buf)));
    c.reencode = [](const Frame& f) {
      std::array<uint8_t, kMaxPayloadLen> out{};
      encode_payload(f.as<M>(), out.data());
      return out;
    };

    json job = {{"name", c.name}, {"msgname", c.msgname}, {"msgid", M::kId}, {"crc_extra", M::kCrcExtra},
                {"max_length", M::kMaxLength}, {"seq", c.seq}, {"sysid", kSysid}, {"compid", kCompid},
                {"hitl_frame", to_hex(c.hitl_frame)}};
    json fields = json::array();
    for (const auto& f : desc->fields) {
      fields.push_back({{"name", f.name}, {"type", std::string(to_string(f.type))}, {"length", f.array_length},
                        {"offset", f.offset}, {"extension", f.extension},
                        {"hex", to_hex(std::span<const uint8_t>(c.payload.data() + f.offset, f.wire_size()))}});
    }
    job["fields"] = std::move(fields);
    if (fill == Fill::Random) {
      c.sign_ms = kSignBaseMs + M::kId;
      const std::size_t n = signer.encode(message, buf);
      c.hitl_signed_frame.assign(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
      job["hitl_signed_frame"] = to_hex(c.hitl_signed_frame);
      job["sign"] = {{"key", to_hex(kKey)}, {"link_id", kLinkId}, {"timestamp_ms", c.sign_ms}};
    }
    jobs.push_back(std::move(job));
    cases.push_back(std::move(c));
  }
}

template <class... Ms>
void add_all_cases(std::vector<Case>& cases, json& jobs, FrameEncoder& encoder, FrameEncoder& signer, const MessageSet& set,
                   TypeList<Ms...>) {
  (add_cases<Ms>(cases, jobs, encoder, signer, set), ...);
}

/// The frame node-mavlink is expected to send for an all-zero message (kAllZeroDeviation in node_mavlink_test.cpp).
inline std::vector<uint8_t> expected_node_all_zero(const std::vector<uint8_t>& hitl_frame, const MessageDesc& desc) {
  std::vector<uint8_t> out(hitl_frame.begin(), hitl_frame.begin() + kHeaderLenV2);
  out[1] = 0;
  uint16_t crc = crc_x25(std::span<const uint8_t>(out.data() + 1, kHeaderLenV2 - 1));
  crc = crc_accumulate(desc.crc_extra, crc);
  out.push_back(static_cast<uint8_t>(crc));
  out.push_back(static_cast<uint8_t>(crc >> 8));
  return out;
}

}  // namespace hitl::mavlink::conformance
