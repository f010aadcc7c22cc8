// The tunnel's framing (base/contract/datagram_framing.h): round trips, reads split and merged
// at every boundary, oversize and malformed frames, the hello.
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "base/contract/datagram_framing.h"

namespace hitl::adb {
namespace {

struct Collected : FrameDecoder::Sink {
  struct Item {
    Channel channel;
    std::vector<uint8_t> payload;
  };
  std::vector<Item> items;
  void on_frame(Channel channel, const uint8_t* payload, std::size_t size) override {
    items.push_back({channel, std::vector<uint8_t>(payload, payload + size)});
  }
};

std::vector<uint8_t> bytes(std::size_t n, uint8_t first = 0) {
  std::vector<uint8_t> v(n);
  std::iota(v.begin(), v.end(), first);
  return v;
}

TEST(Hello, RoundTripAndLayout) {
  std::vector<uint8_t> out;
  append_hello(out, Hello{7, 1500});
  ASSERT_EQ(out.size(), kHelloSize_bytes);
  EXPECT_EQ(std::string(out.begin(), out.begin() + 8), "hitl-adb");
  EXPECT_EQ(out[8], 0);  // big-endian version
  EXPECT_EQ(out[9], 7);
  EXPECT_EQ(out[10], 1500 >> 8);
  EXPECT_EQ(out[11], 1500 & 0xFF);
  const auto parsed = parse_hello(out.data(), out.size());
  ASSERT_TRUE(parsed.hello) << parsed.error;
  EXPECT_EQ(parsed.hello->version, 7);
  EXPECT_EQ(parsed.hello->max_datagram_bytes, 1500);
}

TEST(Hello, SomethingElseIsNamed) {
  const std::string http = "GET / HTTP/1.1\r\n";
  const auto parsed = parse_hello(reinterpret_cast<const uint8_t*>(http.data()), http.size());
  EXPECT_FALSE(parsed.hello);
  EXPECT_EQ(parsed.error, "not a hitl adb tunnel: the stream starts with 'GET / HT', not 'hitl-adb'");
  EXPECT_FALSE(starts_like_hello(reinterpret_cast<const uint8_t*>(http.data()), 3));
  const std::string partial = "hitl";
  EXPECT_TRUE(starts_like_hello(reinterpret_cast<const uint8_t*>(partial.data()), partial.size()));
  EXPECT_NE(parse_hello(reinterpret_cast<const uint8_t*>(partial.data()), partial.size()).error.find("too short"), std::string::npos);
}

TEST(Frames, LayoutIsLengthChannelPayload) {
  std::vector<uint8_t> out;
  const auto p = bytes(300);
  ASSERT_TRUE(append_frame(out, Channel::Vio, p.data(), p.size()));
  ASSERT_EQ(out.size(), 3 + 300u);
  EXPECT_EQ(out[0], 300 >> 8);
  EXPECT_EQ(out[1], 300 & 0xFF);
  EXPECT_EQ(out[2], 2);  // VIO
  EXPECT_TRUE(std::equal(p.begin(), p.end(), out.begin() + 3));
}

TEST(Frames, RoundTripOfManyFramesInOneRead) {
  std::vector<uint8_t> stream;
  const std::vector<std::pair<Channel, std::size_t>> sent = {
      {Channel::Hil, 51}, {Channel::Vio, 0}, {Channel::Gcs, 280}, {Channel::Hil, kMaxDatagram_bytes}, {Channel::Vio, 1}};
  for (const auto& [c, n] : sent) {
    const auto p = bytes(n, static_cast<uint8_t>(n));
    ASSERT_TRUE(append_frame(stream, c, p.data(), p.size()));
  }
  FrameDecoder decoder;
  Collected got;
  ASSERT_TRUE(decoder.feed(stream.data(), stream.size(), got)) << decoder.error();
  ASSERT_EQ(got.items.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(got.items[i].channel, sent[i].first);
    EXPECT_EQ(got.items[i].payload, bytes(sent[i].second, static_cast<uint8_t>(sent[i].second)));
  }
  EXPECT_EQ(decoder.buffered(), 0u);
  EXPECT_EQ(decoder.frames(), sent.size());
}

TEST(Frames, EverySplitPointGivesTheSameFrames) {
  std::vector<uint8_t> stream;
  const auto a = bytes(40, 1), b = bytes(7, 100), c = bytes(0);
  append_frame(stream, Channel::Hil, a.data(), a.size());
  append_frame(stream, Channel::Gcs, b.data(), b.size());
  append_frame(stream, Channel::Vio, c.data(), c.size());
  append_control_frame(stream, {ControlType::Ping, 0x0102030405060708ULL});
  for (std::size_t split = 0; split <= stream.size(); ++split) {
    for (std::size_t chunk : {std::size_t{1}, std::size_t{2}, std::size_t{5}, stream.size()}) {
      FrameDecoder decoder;
      Collected got;
      ASSERT_TRUE(decoder.feed(stream.data(), split, got));
      for (std::size_t at = split; at < stream.size(); at += chunk)
        ASSERT_TRUE(decoder.feed(stream.data() + at, std::min(chunk, stream.size() - at), got)) << decoder.error();
      ASSERT_EQ(got.items.size(), 4u) << "split " << split << " chunk " << chunk;
      EXPECT_EQ(got.items[0].payload, a);
      EXPECT_EQ(got.items[1].channel, Channel::Gcs);
      EXPECT_EQ(got.items[1].payload, b);
      EXPECT_TRUE(got.items[2].payload.empty());
      EXPECT_EQ(got.items[3].channel, Channel::Control);
      const auto control = parse_control(got.items[3].payload.data(), got.items[3].payload.size());
      ASSERT_TRUE(control);
      EXPECT_EQ(control->type, ControlType::Ping);
      EXPECT_EQ(control->value, 0x0102030405060708ULL);
      EXPECT_EQ(decoder.buffered(), 0u);
    }
  }
}

TEST(Frames, OversizePayloadIsRefusedWhenFramed) {
  std::vector<uint8_t> out;
  const auto p = bytes(kMaxDatagram_bytes + 1);
  EXPECT_FALSE(append_frame(out, Channel::Hil, p.data(), p.size()));
  EXPECT_TRUE(out.empty());
}

TEST(Frames, OversizeFrameOnTheStreamIsMalformedAndStaysSo) {
  const auto good = bytes(10);
  std::vector<uint8_t> stream;
  append_frame(stream, Channel::Hil, good.data(), good.size());
  const uint16_t too_long = kMaxDatagram_bytes + 1;
  stream.insert(stream.end(), {static_cast<uint8_t>(too_long >> 8), static_cast<uint8_t>(too_long & 0xFF), 1});
  FrameDecoder decoder;
  Collected got;
  EXPECT_FALSE(decoder.feed(stream.data(), stream.size(), got));
  EXPECT_EQ(got.items.size(), 1u);  // the frame before it was delivered
  EXPECT_EQ(decoder.error(), "malformed frame 2: 8193 bytes on the HIL channel, over the limit of 8192");
  // Nothing after a bad header can be trusted to start on a frame boundary.
  EXPECT_FALSE(decoder.feed(stream.data(), 13, got));
  EXPECT_EQ(got.items.size(), 1u);
}

TEST(Frames, OversizeHeaderSplitAcrossReadsIsMalformed) {
  const uint8_t header[3] = {0xFF, 0xFF, 1};
  FrameDecoder decoder;
  Collected got;
  EXPECT_TRUE(decoder.feed(header, 2, got));
  EXPECT_FALSE(decoder.feed(header + 2, 1, got));
  EXPECT_NE(decoder.error().find("65535 bytes"), std::string::npos) << decoder.error();
}

TEST(Frames, UnknownChannelIsMalformed) {
  const uint8_t frame[] = {0, 2, 9, 0xAA, 0xBB};
  FrameDecoder decoder;
  Collected got;
  EXPECT_FALSE(decoder.feed(frame, sizeof frame, got));
  EXPECT_EQ(decoder.error(), "malformed frame 1: unknown channel 9 (length 2)");
  EXPECT_TRUE(got.items.empty());
}

TEST(Frames, DecoderHoldsAtMostOneFrame) {
  const auto p = bytes(kMaxDatagram_bytes);
  std::vector<uint8_t> stream;
  append_frame(stream, Channel::Gcs, p.data(), p.size());
  FrameDecoder decoder;
  Collected got;
  ASSERT_TRUE(decoder.feed(stream.data(), stream.size() - 1, got));
  EXPECT_EQ(decoder.buffered(), stream.size() - 1);
  ASSERT_TRUE(decoder.feed(stream.data() + stream.size() - 1, 1, got));
  EXPECT_EQ(decoder.buffered(), 0u);
  ASSERT_EQ(got.items.size(), 1u);
  EXPECT_EQ(got.items[0].payload, p);
}

TEST(Control, RoundTripAndRejects) {
  std::vector<uint8_t> out;
  append_control_frame(out, {ControlType::Pong, 42});
  ASSERT_EQ(out.size(), 3 + kControlSize_bytes);
  EXPECT_EQ(out[2], 0);  // the control channel
  const auto m = parse_control(out.data() + 3, kControlSize_bytes);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, ControlType::Pong);
  EXPECT_EQ(m->value, 42u);
  EXPECT_FALSE(parse_control(out.data() + 3, kControlSize_bytes - 1));
  uint8_t unknown[kControlSize_bytes] = {77};
  EXPECT_FALSE(parse_control(unknown, sizeof unknown));
}

}  // namespace
}  // namespace hitl::adb
