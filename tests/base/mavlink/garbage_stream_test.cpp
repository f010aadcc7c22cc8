// Issue 19 point 5: junk between good frames. Every intact frame comes out, nothing false is
// taken for a message, and a frame of an unknown id (no checkable checksum) is passed on only
// when its framing is whole, so a stray start byte never swallows the frames after it.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/messages.h"

namespace hitl::mavlink {
namespace {

using Bytes = std::vector<uint8_t>;

template <class M>
Bytes encode(FrameEncoder& enc, const M& m) {
  FrameBuffer buf;
  const std::size_t n = enc.encode(m, buf);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

Bytes good_frame(FrameEncoder& enc, int i) {
  switch (i % 4) {
    case 0: return encode(enc, gcs_heartbeat());
    case 1: {
      msg::Odometry o;
      o.time_usec = static_cast<uint64_t>(i) * 4000;
      o.q = {1, 0, 0, 0};
      return encode(enc, o);
    }
    case 2: {
      msg::HilSensor s;
      s.time_usec = static_cast<uint64_t>(i);
      s.zacc = -9.81f;
      return encode(enc, s);
    }
    default: {
      msg::Attitude a;
      a.time_boot_ms = static_cast<uint32_t>(i);
      a.roll = 0.1f;
      return encode(enc, a);
    }
  }
}

// Junk rich in start bytes, with plausible headers of unknown ids and random lengths.
Bytes junk(std::mt19937& rng) {
  Bytes j(rng() % 300);
  for (auto& b : j) {
    const unsigned r = rng() % 10;
    b = r == 0 ? kStxV2 : r == 1 ? kStxV1 : static_cast<uint8_t>(rng());
  }
  return j;
}

struct Stream {
  Bytes bytes;
  std::vector<Bytes> good;
};

Stream garbage_stream(unsigned seed, int frames) {
  std::mt19937 rng(seed);
  FrameEncoder enc(1, 1);
  Stream s;
  for (int i = 0; i < frames; ++i) {
    const Bytes j = junk(rng);
    s.bytes.insert(s.bytes.end(), j.begin(), j.end());
    s.good.push_back(good_frame(enc, i));
    s.bytes.insert(s.bytes.end(), s.good.back().begin(), s.good.back().end());
  }
  const Bytes tail = junk(rng);
  s.bytes.insert(s.bytes.end(), tail.begin(), tail.end());
  return s;
}

struct Outcome {
  int recovered = 0;  ///< good frames delivered, in order
  int false_messages = 0;  ///< frames of a known id that were not one of the good frames
  int unverified = 0;  ///< frames of an unknown id passed on (whole framing)
};

Outcome judge(const Stream& s, const std::vector<Bytes>& delivered_known, int unknown) {
  Outcome o;
  o.unverified = unknown;
  std::size_t next = 0;
  for (const auto& f : delivered_known) {
    const auto it = std::find(s.good.begin() + static_cast<std::ptrdiff_t>(next), s.good.end(), f);
    if (it == s.good.end()) {
      ++o.false_messages;
      continue;
    }
    ++o.recovered;
    next = static_cast<std::size_t>(it - s.good.begin()) + 1;
  }
  return o;
}

TEST(GarbageStream, EveryIntactFrameAndNoFalseMessageAsDatagram) {
  const MessageSet set = MessageSet::compiled();
  int recovered = 0, false_messages = 0, unverified = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Stream s = garbage_stream(seed, 41);
    FrameParser parser(set);
    std::vector<Bytes> known;
    int unknown = 0;
    parser.parse_datagram(s.bytes, [&](const Frame& f) {
      if (f.desc == nullptr) ++unknown;
      else known.emplace_back(f.bytes().begin(), f.bytes().end());
    });
    const Outcome o = judge(s, known, unknown);
    EXPECT_EQ(o.recovered, 41) << "seed " << seed;
    EXPECT_EQ(o.false_messages, 0) << "seed " << seed;
    EXPECT_EQ(parser.stats().unknown_ids, static_cast<uint64_t>(unknown));
    EXPECT_GE(parser.stats().unverified, parser.stats().unverified_dropped + parser.stats().unknown_ids);
    recovered += o.recovered;
    false_messages += o.false_messages;
    unverified += o.unverified;
  }
  std::printf("20 garbage datagrams: %d/820 recovered, %d false messages, %d unknown-id frames passed on\n", recovered,
              false_messages, unverified);
}

TEST(GarbageStream, EveryIntactFrameAndNoFalseMessageAsStream) {
  const MessageSet set = MessageSet::compiled();
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Stream s = garbage_stream(seed, 41);
    FrameParser parser(set);
    std::vector<Bytes> known;
    int unknown = 0;
    std::mt19937 rng(seed * 7);
    // A live stream goes on: a start byte near the end may wait for up to a frame's length.
    s.bytes.resize(s.bytes.size() + kMaxFrameLen, 0);
    for (std::size_t pos = 0; pos < s.bytes.size();) {
      const std::size_t n = std::min<std::size_t>(1 + rng() % 200, s.bytes.size() - pos);
      parser.feed({s.bytes.data() + pos, n}, [&](const Frame& f) {
        if (f.desc == nullptr) ++unknown;
        else known.emplace_back(f.bytes().begin(), f.bytes().end());
      });
      pos += n;
    }
    const Outcome o = judge(s, known, unknown);
    EXPECT_EQ(o.recovered, 41) << "seed " << seed;
    EXPECT_EQ(o.false_messages, 0) << "seed " << seed;
  }
}

TEST(GarbageStream, StrayStartByteOfAnUnknownIdDoesNotSwallowTheNextFrame) {
  const MessageSet set = MessageSet::compiled();
  FrameEncoder enc(1, 1);
  // v1, length 251: the false frame of issue 19 (id 247, COLLISION: not compiled in, but in the
  // official XML, so now its checksum is checked), and the same with 240, an id outside the XML,
  // which the unknown-id rule still judges by its framing.
  for (const uint8_t id : {uint8_t{247}, uint8_t{240}}) {
    SCOPED_TRACE(id);
    ASSERT_EQ(find_standard_check(id) != nullptr, id == 247);
    Bytes bytes = {kStxV1, 251, 0, 1, 1, id};
    const Bytes good = encode(enc, gcs_heartbeat());
    bytes.insert(bytes.end(), good.begin(), good.end());
    bytes.resize(bytes.size() + 260, 0x55);
    FrameParser parser(set);
    std::vector<Frame> out;
    parser.parse_datagram(bytes, [&](const Frame& f) { out.push_back(f); });
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NE(out[0].desc, nullptr);
    EXPECT_EQ(parser.stats().unknown_ids, 0u);
    EXPECT_GE(id == 247 ? parser.stats().crc_errors : parser.stats().unverified_dropped, 1u);
  }
}

TEST(GarbageStream, UnknownIdWithWholeFramingIsPassedOn) {
  const MessageSet set = MessageSet::compiled();
  FrameEncoder enc(1, 1);
  FrameBuffer buf;
  const Bytes payload = {1, 2, 3};
  const std::size_t n = enc.encode_raw(60001, 99, payload, 3, buf);
  Bytes bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  const Bytes good = encode(enc, gcs_heartbeat());
  bytes.insert(bytes.end(), good.begin(), good.end());  // ends at the next start byte
  bytes.insert(bytes.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));  // ends at the datagram's end
  FrameParser parser(set);
  int unknown = 0, known = 0;
  parser.parse_datagram(bytes, [&](const Frame& f) { (f.desc == nullptr ? unknown : known)++; });
  EXPECT_EQ(unknown, 2);
  EXPECT_EQ(known, 1);
  // Followed by junk instead: its framing is not whole, so it is dropped.
  Bytes followed(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  followed.push_back(0x42);
  FrameParser strict(set);
  unknown = 0;
  strict.parse_datagram(followed, [&](const Frame& f) { unknown += f.desc == nullptr; });
  EXPECT_EQ(unknown, 0);
  EXPECT_EQ(strict.stats().unverified_dropped, 1u);
}

}  // namespace
}  // namespace hitl::mavlink
