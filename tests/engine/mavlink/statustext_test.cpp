#include "engine/mavlink/statustext.h"

#include <gtest/gtest.h>

#include <string>

#include "base/mavlink/text_field.h"

namespace hitl::mavlink {
namespace {

msg::Statustext chunk(uint16_t id, uint8_t seq, const std::string& text, uint8_t severity = 2) {
  msg::Statustext t;
  t.severity = severity;
  t.id = id;
  t.chunk_seq = seq;
  set_text(t.text, text);
  return t;
}

const std::string kFifty(50, 'a');

TEST(StatusTextAssembler, AShortTextComesOutAtOnce) {
  StatusTextAssembler a;
  const auto out = a.on_statustext(1, 1, chunk(0, 0, "Takeoff detected", 6), 10.0);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].text, "Takeoff detected");
  EXPECT_EQ(out[0].severity, 6);
  EXPECT_EQ(out[0].chunks, 1);
  EXPECT_FALSE(out[0].incomplete);
}

TEST(StatusTextAssembler, Px4sTwoChunksAreOneText) {
  // PX4's arming refusal, 56 characters: 50 in chunk 0, the rest and a NUL in chunk 1.
  const std::string text = "Arming temporarily rejected: the estimator is not ready";
  StatusTextAssembler a;
  EXPECT_TRUE(a.on_statustext(1, 1, chunk(3, 0, text.substr(0, 50)), 1.0).empty());
  const auto out = a.on_statustext(1, 1, chunk(3, 1, text.substr(50)), 1.001);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].text, text);
  EXPECT_EQ(out[0].chunks, 2);
  EXPECT_FALSE(out[0].incomplete);
  EXPECT_TRUE(a.flush().empty());
}

TEST(StatusTextAssembler, ATextThatFillsItsChunkWaitsForTheNextOrTheWait) {
  StatusTextAssembler a;
  EXPECT_TRUE(a.on_statustext(1, 1, chunk(4, 0, kFifty), 1.0).empty());
  EXPECT_TRUE(a.expire(1.0 + StatusTextAssembler::kChunkWait_s / 2).empty());
  auto out = a.expire(1.0 + StatusTextAssembler::kChunkWait_s);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].text, kFifty);
  EXPECT_FALSE(out[0].incomplete);  // PX4 sends no closing chunk for an exact fill

  EXPECT_TRUE(a.on_statustext(1, 1, chunk(5, 0, kFifty), 2.0).empty());
  out = a.on_statustext(1, 1, chunk(6, 0, "next"), 2.01);  // the source's next text closes it
  ASSERT_EQ(out.size(), 2U);
  EXPECT_EQ(out[0].text, kFifty);
  EXPECT_EQ(out[1].text, "next");
}

TEST(StatusTextAssembler, AMissingChunkIsMarkedAsPx4MarksIt) {
  StatusTextAssembler a;
  EXPECT_TRUE(a.on_statustext(1, 1, chunk(9, 0, kFifty), 1.0).empty());
  const auto out = a.on_statustext(1, 1, chunk(9, 2, "end"), 1.0);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].text, kFifty + "[ missing ... ]end");
  EXPECT_TRUE(out[0].incomplete);
  // A text whose first chunk never came.
  const auto late = a.on_statustext(1, 1, chunk(10, 1, "tail"), 2.0);
  ASSERT_EQ(late.size(), 1U);
  EXPECT_EQ(late[0].text, "[ missing ... ]tail");
  EXPECT_TRUE(late[0].incomplete);
}

TEST(StatusTextAssembler, SourcesAreAssembledApart) {
  StatusTextAssembler a;
  EXPECT_TRUE(a.on_statustext(1, 1, chunk(1, 0, kFifty), 1.0).empty());
  EXPECT_TRUE(a.on_statustext(2, 1, chunk(1, 0, std::string(50, 'b')), 1.0).empty());
  auto one = a.on_statustext(1, 1, chunk(1, 1, "1"), 1.0);
  auto two = a.on_statustext(2, 1, chunk(1, 1, "2"), 1.0);
  ASSERT_EQ(one.size(), 1U);
  ASSERT_EQ(two.size(), 1U);
  EXPECT_EQ(one[0].text, kFifty + "1");
  EXPECT_EQ(two[0].text, std::string(50, 'b') + "2");
}

TEST(StatusTextAssembler, WhatASenderCanMakeItHoldIsBounded) {
  StatusTextAssembler a;
  // An endless text: given out, cut, every kMaxChunks chunks.
  std::size_t given = 0, longest = 0;
  for (int seq = 0; seq < 255; ++seq)
    for (const auto& t : a.on_statustext(1, 1, chunk(7, static_cast<uint8_t>(seq), kFifty), 1.0)) {
      ++given;
      longest = std::max(longest, t.text.size());
      EXPECT_TRUE(t.incomplete);
    }
  EXPECT_GE(given, 255U / StatusTextAssembler::kMaxChunks - 1);
  EXPECT_LE(longest, StatusTextAssembler::kMaxChunks * (50 + 15U));
  // Many sources at once: at most kMaxPending held.
  for (int sys = 0; sys < 255; ++sys) a.on_statustext(static_cast<uint8_t>(sys), 1, chunk(1, 0, kFifty), 2.0);
  EXPECT_LE(a.flush().size(), StatusTextAssembler::kMaxPending);
}

TEST(StatusTextAssembler, PrintableTextHasNoControlCharacters) {
  EXPECT_EQ(printable_statustext("a\tb\x1b[2Jc\x7f"), "a b [2Jc ");
}

}  // namespace
}  // namespace hitl::mavlink

namespace hitl::mavlink {
namespace {

std::string joined(StatusTextAssembler& a, const std::vector<msg::Statustext>& chunks) {
  std::string text;
  for (const auto& c : chunks)
    for (const auto& t : a.on_statustext(1, 1, c, 1.0)) text += t.text;
  for (const auto& t : a.flush()) text += t.text;
  return text;
}

TEST(StatusTextChunker, SplitsAsPx4AndTheAssemblerJoins) {
  StatusTextChunker c;
  StatusTextAssembler a;
  const auto one = c.split(4, "short");
  ASSERT_EQ(one.size(), 1U);
  EXPECT_EQ(one[0].id, 0);  // the only chunk
  const std::string long_text(120, 'x');
  const auto three = c.split(4, long_text);
  ASSERT_EQ(three.size(), 3U);
  EXPECT_NE(three[0].id, 0);
  EXPECT_EQ(three[0].id, three[2].id);
  EXPECT_EQ(three[2].chunk_seq, 2);
  EXPECT_EQ(joined(a, three), long_text);
  const auto exact = c.split(4, std::string(100, 'y'));  // fills its last chunk: no closing chunk
  ASSERT_EQ(exact.size(), 2U);
  EXPECT_NE(exact[1].id, three[0].id);
  EXPECT_EQ(joined(a, exact), std::string(100, 'y'));
  EXPECT_EQ(c.split(4, std::string(1000, 'z')).size(), static_cast<std::size_t>(StatusTextAssembler::kMaxChunks));
}

}  // namespace
}  // namespace hitl::mavlink
