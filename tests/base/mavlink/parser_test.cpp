// The streaming parser: resync after garbage, CRC, truncation, unknown ids, v1,
// incompat flags, signing, split input, and every counter.
#include <gtest/gtest.h>

#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"

namespace hitl::mavlink {
namespace {

class ParserTest : public ::testing::Test {
 protected:
  template <class M>
  std::vector<uint8_t> frame(const M& m, FrameEncoder& enc) {
    FrameBuffer buf;
    const std::size_t n = enc.encode(m, buf);
    return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
  }
  template <class M>
  std::vector<uint8_t> frame(const M& m) {
    return frame(m, encoder_);
  }
  std::vector<Frame> parse(const std::vector<uint8_t>& bytes, FrameParser& parser) {
    std::vector<Frame> out;
    parser.parse_datagram(bytes, [&](const Frame& f) { out.push_back(f); });
    return out;
  }
  static msg::HilSensor sensor() {
    msg::HilSensor s;
    s.time_usec = 123456;
    s.zacc = -9.81f;
    s.abs_pressure = 1013.25f;
    s.fields_updated = 0x1FFF;
    s.id = 0;
    return s;
  }

  MessageSet set_ = MessageSet::compiled();
  FrameEncoder encoder_{1, 1};
};

TEST_F(ParserTest, ResynchronisesAfterGarbageAndCountsIt) {
  std::vector<uint8_t> bytes = {0x00, 0x13, 0x37, 0xFD, 0x05};  // garbage, including a false STX
  auto f = frame(sensor());
  bytes.insert(bytes.end(), f.begin(), f.end());
  bytes.insert(bytes.end(), {0xAA, 0xBB});
  bytes.insert(bytes.end(), f.begin(), f.end());
  FrameParser parser(set_);
  auto frames = parse(bytes, parser);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_FLOAT_EQ(frames[0].as<msg::HilSensor>().zacc, -9.81f);
  EXPECT_EQ(parser.stats().parse_errors, 2u);
  EXPECT_EQ(parser.stats().garbage_bytes, 7u);
}

TEST_F(ParserTest, CrcErrorIsCountedAndTheNextFrameStillParses) {
  auto bad = frame(sensor());
  bad[15] ^= 0xFF;  // corrupt the payload
  auto good = frame(sensor());
  bad.insert(bad.end(), good.begin(), good.end());
  FrameParser parser(set_);
  auto frames = parse(bad, parser);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(parser.stats().crc_errors, 1u);
}

TEST_F(ParserTest, FrameHiddenBehindABogusHeaderIsRecovered) {
  // 0xFD with a long length would swallow the real frame if the parser waited for it.
  std::vector<uint8_t> bytes = {0xFD, 200, 0, 0, 0, 1, 1, 0, 0, 0};
  auto f = frame(sensor());
  bytes.insert(bytes.end(), f.begin(), f.end());
  FrameParser parser(set_);
  auto frames = parse(bytes, parser);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_GE(parser.stats().truncated, 1u);
}

TEST_F(ParserTest, TruncatedV2PayloadIsZeroExtended) {
  msg::HilSensor s;  // all zeros after time_usec: the encoder drops the trailing zeros
  s.time_usec = 7;
  auto f = frame(s);
  EXPECT_LT(f[1], msg::HilSensor::kMaxLength);
  EXPECT_EQ(f[1], 1);  // only the low byte of time_usec is left
  FrameParser parser(set_);
  auto frames = parse(f, parser);
  ASSERT_EQ(frames.size(), 1u);
  const auto back = frames[0].as<msg::HilSensor>();
  EXPECT_EQ(back.time_usec, 7u);
  EXPECT_EQ(back.fields_updated, 0u);
  EXPECT_EQ(back.id, 0);
}

TEST_F(ParserTest, AllZeroPayloadKeepsOneByte) {
  msg::HilSensor s;
  auto f = frame(s);
  EXPECT_EQ(f[1], 1);
}

TEST_F(ParserTest, UnknownIdIsPassedOnRawAndCounted) {
  std::vector<uint8_t> payload = {1, 2, 3};
  FrameBuffer buf;
  const std::size_t n = encoder_.encode_raw(60001, 99, payload, 3, buf);
  FrameParser parser(set_);
  auto frames = parse({buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)}, parser);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].desc, nullptr);
  EXPECT_EQ(frames[0].msgid, 60001u);
  EXPECT_EQ(frames[0].raw_len, n);
  EXPECT_EQ(parser.stats().unknown_ids, 1u);
}

// Issue 27: junk with a standard id hitl has no type for (SET_MODE, #11) passed unchecked; every id
// of the official XML now has its checksum checked.
TEST_F(ParserTest, StandardButUntypedIdIsCheckedByItsCrc) {
  const MessageCheck* set_mode = find_standard_check(11);
  ASSERT_NE(set_mode, nullptr);
  EXPECT_EQ(set_mode->crc_extra, 89);
  EXPECT_EQ(set_mode->min_length, 6);
  EXPECT_EQ(set_mode->flags, MessageCheck::kHasTargetSystem);
  EXPECT_EQ(set_mode->target_system_offset, 4);
  ASSERT_EQ(set_.find(11u), nullptr);  // not typed: this test is about the table
  const std::vector<uint8_t> payload = {1, 0, 0, 0, 7, 1};
  FrameBuffer buf;
  FrameParser parser(set_);
  const std::size_t bad = encoder_.encode_raw(11, set_mode->crc_extra ^ 0x5A, payload, 6, buf);
  EXPECT_TRUE(parse({buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(bad)}, parser).empty());
  EXPECT_EQ(parser.stats().crc_errors, 1u);
  EXPECT_EQ(parser.stats().unverified, 0u);
  const std::size_t good = encoder_.encode_raw(11, set_mode->crc_extra, payload, 6, buf);
  auto frames = parse({buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(good)}, parser);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].desc, nullptr);
  EXPECT_EQ(frames[0].check, set_mode);
  EXPECT_EQ(parser.stats().untyped_frames, 1u);
  EXPECT_EQ(parser.stats().unknown_ids, 0u);
}

TEST_F(ParserTest, TheStandardTableIsSortedAndHoldsEveryTypedMessage) {
  const auto& table = msg::kStandardChecks;
  EXPECT_GT(table.size(), 200u);
  for (std::size_t i = 1; i < table.size(); ++i) EXPECT_LT(table[i - 1].id, table[i].id);
  for (const auto* desc : set_.all()) {
    const MessageCheck* c = find_standard_check(desc->id);
    ASSERT_NE(c, nullptr) << desc->name;
    EXPECT_EQ(c->crc_extra, desc->crc_extra) << desc->name;
    EXPECT_EQ(c->min_length, desc->min_length) << desc->name;
    EXPECT_EQ(c->max_length, desc->max_length) << desc->name;
  }
  EXPECT_EQ(find_standard_check(60001), nullptr);  // outside the XML: the unknown-id rule
}

TEST_F(ParserTest, MavlinkV1FramesParse) {
  FrameEncoder v1(3, 4, Version::V1);
  msg::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = 12;
  hb.custom_mode = 0x01020304;
  auto f = frame(hb, v1);
  EXPECT_EQ(f[0], kStxV1);
  EXPECT_EQ(f.size(), kHeaderLenV1 + msg::Heartbeat::kMinLength + kChecksumLen);
  FrameParser parser(set_);
  auto frames = parse(f, parser);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].version, Version::V1);
  EXPECT_EQ(frames[0].as<msg::Heartbeat>().custom_mode, 0x01020304u);
  EXPECT_EQ(parser.stats().v1_frames, 1u);
  // A message id above 255 cannot be sent as v1.
  FrameBuffer buf;
  EXPECT_EQ(v1.encode(msg::Odometry{}, buf), 0u);
}

TEST_F(ParserTest, UnknownIncompatFlagsAreRejected) {
  auto f = frame(sensor());
  f[2] = 0x02;
  FrameParser parser(set_);
  EXPECT_TRUE(parse(f, parser).empty());
  EXPECT_GE(parser.stats().bad_incompat_flags, 1u);
}

TEST_F(ParserTest, StreamSplitAtEveryByteGivesTheSameFrames) {
  std::vector<uint8_t> stream;
  for (int i = 0; i < 3; ++i) {
    auto f = frame(sensor());
    stream.insert(stream.end(), f.begin(), f.end());
  }
  FrameParser parser(set_);
  int frames = 0;
  for (uint8_t b : stream) parser.feed({&b, 1}, [&](const Frame&) { ++frames; });
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(parser.stats().parse_errors, 0u);
}

TEST_F(ParserTest, PartialFrameAtTheEndOfADatagramIsTruncated) {
  auto f = frame(sensor());
  f.resize(f.size() - 5);
  FrameParser parser(set_);
  EXPECT_TRUE(parse(f, parser).empty());
  EXPECT_EQ(parser.stats().truncated, 1u);
}

TEST_F(ParserTest, SignedFramesVerifyAndBadOnesAreCounted) {
  const SigningKey key = *parse_signing_key("hitl");
  FrameEncoder signer(1, 1);
  signer.set_signing(key, 5);
  auto f1 = frame(sensor(), signer);
  auto f2 = frame(sensor(), signer);
  EXPECT_EQ(f1.size(), kHeaderLenV2 + f1[1] + kChecksumLen + kSignatureLen);

  FrameParser verifying(set_, ParserOptions{key, true});
  auto frames = parse(f1, verifying);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(frames[0].is_signed());
  EXPECT_EQ(frames[0].signature_link_id(), 5);
  // Replaying the same frame is refused (its timestamp does not advance).
  EXPECT_TRUE(parse(f1, verifying).empty());
  EXPECT_EQ(verifying.stats().signature_errors, 1u);
  EXPECT_EQ(parse(f2, verifying).size(), 1u);

  FrameParser wrong_key(set_, ParserOptions{*parse_signing_key("other"), true});
  EXPECT_TRUE(parse(f2, wrong_key).empty());
  EXPECT_EQ(wrong_key.stats().signature_errors, 1u);

  FrameParser strict(set_, ParserOptions{key, false});
  EXPECT_TRUE(parse(frame(sensor()), strict).empty());
  EXPECT_EQ(strict.stats().unsigned_rejected, 1u);

  FrameParser no_key(set_);
  EXPECT_EQ(parse(f2, no_key).size(), 1u);  // without a key, signed frames pass unverified
}

TEST_F(ParserTest, SequenceNumbersIncreaseAndWrap) {
  FrameEncoder enc(1, 1);
  FrameBuffer buf;
  for (int i = 0; i < 300; ++i) {
    enc.encode(msg::Heartbeat{}, buf);
    EXPECT_EQ(buf[4], static_cast<uint8_t>(i));
  }
}

}  // namespace
}  // namespace hitl::mavlink
