// libFuzzer target for hitl::mavlink::FrameParser.
//
// Each input is parsed four ways: as one datagram and as a stream split at an
// input-derived point (then the tail fed in small chunks), each without a key and with
// the signing key of the seed corpus (tests/fuzz/fuzz_key.h; the stream parser then also
// refuses unsigned frames). Every delivered frame is printed (format_message), turned into
// JSON (fields_to_json, dumped as the CLI does) and, for compiled-in ids, decoded with
// as<M>() and re-encoded. Sanitizers catch crashes, UB and leaks; the invariants below
// are checked with __builtin_trap().
//
// Build and run: see tests/fuzz/run.sh and docs/codec.md.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

#include "base/mavlink/crc.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"
#include "engine/mavlink/field_format.h"
#include "tests/fuzz/fuzz_key.h"

namespace {

using namespace hitl::mavlink;

#define FUZZ_CHECK(cond) \
  do {                   \
    if (!(cond)) __builtin_trap(); \
  } while (0)

const MessageSet& messages() {
  static const MessageSet set = MessageSet::compiled();
  return set;
}

/// as<M>() for the compiled-in message with this id; the re-encoded payload must equal the received one.
template <class... Ms>
void decode_typed(const Frame& frame, TypeList<Ms...>) {
  auto one = [&](auto tag) {
    using M = decltype(tag);
    if (!frame.is<M>()) return;
    const M m = frame.as<M>();
    std::array<uint8_t, kMaxPayloadLen> again{};
    encode_payload(m, again.data());
    FUZZ_CHECK(std::memcmp(again.data(), frame.payload.data(), M::kMaxLength) == 0);
  };
  (one(Ms{}), ...);
}

struct Seen {
  uint64_t frames = 0;
  uint64_t v1 = 0;
  uint64_t signed_ = 0;
  uint64_t unknown = 0;
  uint64_t raw_bytes = 0;
};

void check_frame(const Frame& f, Seen& seen, bool must_be_signed) {
  ++seen.frames;
  seen.raw_bytes += f.raw_len;
  FUZZ_CHECK(f.raw_len <= kMaxFrameLen);
  FUZZ_CHECK(f.payload_len <= kMaxPayloadLen);
  const bool v2 = f.version == Version::V2;
  FUZZ_CHECK(f.raw[0] == (v2 ? kStxV2 : kStxV1));
  FUZZ_CHECK(f.raw[1] == f.payload_len);
  FUZZ_CHECK(f.raw_len == (v2 ? kHeaderLenV2 : kHeaderLenV1) + f.payload_len + kChecksumLen + (f.is_signed() ? kSignatureLen : 0));
  FUZZ_CHECK(v2 || f.incompat_flags == 0);
  FUZZ_CHECK((f.incompat_flags & ~kIncompatFlagSigned) == 0);
  FUZZ_CHECK(!must_be_signed || f.is_signed());
  for (std::size_t i = f.payload_len; i < kMaxPayloadLen; ++i) FUZZ_CHECK(f.payload[i] == 0);  // zero-extended
  if (f.version == Version::V1) ++seen.v1;
  if (f.is_signed()) ++seen.signed_;
  if (f.desc == nullptr && f.check == nullptr) {
    ++seen.unknown;
  } else {
    // A delivered frame of a known id (typed or of the official XML) has a good checksum.
    const std::size_t header = v2 ? kHeaderLenV2 : kHeaderLenV1;
    const uint8_t crc_extra = f.desc != nullptr ? f.desc->crc_extra : f.check->crc_extra;
    const uint16_t crc = crc_accumulate(crc_extra, crc_x25(std::span<const uint8_t>(f.raw.data() + 1, header - 1 + f.payload_len)));
    FUZZ_CHECK(crc == f.checksum);
    FUZZ_CHECK((f.desc != nullptr ? f.desc->id : f.check->id) == f.msgid);
  }

  const std::string text = format_message(f);
  FUZZ_CHECK(!text.empty());
  const nlohmann::json fields = fields_to_json(f);
  // Strings from the wire need not be UTF-8: dump as the CLI does (cli/common_options.cpp).
  const std::string dumped = fields.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  FUZZ_CHECK(!dumped.empty());
  if (f.desc != nullptr) decode_typed(f, msg::All{});
}

void check_stats(const ParserStats& s, const Seen& seen, std::size_t fed, bool datagram, bool keyed) {
  FUZZ_CHECK(s.frames == seen.frames);
  FUZZ_CHECK(s.v1_frames == seen.v1);
  FUZZ_CHECK(s.signed_frames == seen.signed_);
  FUZZ_CHECK(s.unknown_ids == seen.unknown);
  FUZZ_CHECK(s.bytes == fed);
  FUZZ_CHECK(s.garbage_bytes <= s.bytes);
  FUZZ_CHECK(s.parse_errors <= s.garbage_bytes);
  FUZZ_CHECK(seen.raw_bytes + s.garbage_bytes <= s.bytes);
  // A datagram is consumed completely: without a key every byte is in a frame or garbage.
  if (datagram && !keyed) FUZZ_CHECK(seen.raw_bytes + s.garbage_bytes == s.bytes);
  if (!keyed) FUZZ_CHECK(s.signature_errors == 0 && s.unsigned_rejected == 0);
  if (!datagram) FUZZ_CHECK(s.truncated == 0);  // a stream waits for the rest of a frame
  // Each rejection or truncation drops at least one byte as garbage.
  FUZZ_CHECK(s.crc_errors + s.bad_incompat_flags + s.truncated + s.unverified_dropped <= s.garbage_bytes);
  // Every unknown-id frame delivered or dropped was an unverified candidate.
  FUZZ_CHECK(s.unknown_ids + s.unverified_dropped <= s.unverified);
}

void run(std::span<const uint8_t> data, bool keyed, std::size_t split, std::size_t chunk) {
  ParserOptions options;
  if (keyed) options.signing_key = hitl::fuzz::kFuzzKey;

  {  // one datagram
    FrameParser parser(messages(), options);
    Seen seen;
    parser.parse_datagram(data, [&](const Frame& f) { check_frame(f, seen, false); });
    check_stats(parser.stats(), seen, data.size(), true, keyed);
  }
  {  // a stream: the head, then the tail in chunks; with a key, unsigned frames are refused
    ParserOptions stream_options = options;
    if (keyed) stream_options.accept_unsigned = false;
    FrameParser parser(messages(), stream_options);
    Seen seen;
    auto on_frame = [&](const Frame& f) { check_frame(f, seen, keyed); };
    parser.feed(data.first(split), on_frame);
    for (std::size_t pos = split; pos < data.size(); pos += chunk) parser.feed(data.subspan(pos, std::min(chunk, data.size() - pos)), on_frame);
    check_stats(parser.stats(), seen, data.size(), false, keyed);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  const std::span<const uint8_t> data(bytes, size);
  // Split point and chunk size from the last byte, so the frames at the start of a seed stay intact.
  const uint8_t control = size ? bytes[size - 1] : 0;
  const std::size_t split = size * control / 255;
  const std::size_t chunk = 1 + (control % 7) * 37;  // 1 (byte by byte) .. 223
  run(data, false, split, chunk);
  run(data, true, split, chunk);
  return 0;
}
