#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/sequence_tracker.h"
#include "base/mavlink/typed_codec.h"
#include "engine/mavlink/dialect_xml.h"
#include "engine/mavlink/tlog.h"
#include "tests/support/process.h"

namespace hitl::mavlink {
namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(Dialect, LoadsMessagesWithIncludesInWireOrder) {
  const auto dir = test::temp_dir();
  write(dir + "/base.xml", R"(<?xml version="1.0"?>
<mavlink><messages>
  <message id="0" name="HEARTBEAT">
    <field type="uint8_t" name="type">t</field>
    <field type="uint8_t" name="autopilot">a</field>
    <field type="uint8_t" name="base_mode">b</field>
    <field type="uint32_t" name="custom_mode">c</field>
    <field type="uint8_t" name="system_status">s</field>
    <field type="uint8_t_mavlink_version" name="mavlink_version">v</field>
  </message>
</messages></mavlink>)");
  write(dir + "/mine.xml", R"(<?xml version="1.0"?>
<mavlink><include>base.xml</include><messages>
  <message id="60000" name="MY_THING">
    <field type="uint8_t" name="flag">f</field>
    <field type="double" name="value" units="m">v</field>
    <field type="char[8]" name="label">l</field>
    <extensions/>
    <field type="uint16_t" name="extra">e</field>
  </message>
</messages></mavlink>)");
  MessageSet set;
  auto info = load_dialect(dir + "/mine.xml", set);
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->messages, 2u);
  const auto* hb = set.find(0u);
  ASSERT_NE(hb, nullptr);
  EXPECT_EQ(hb->crc_extra, msg::Heartbeat::kCrcExtra);
  EXPECT_EQ(hb->fields[0].name, "custom_mode");  // the uint32 goes first on the wire
  const auto* mine = set.find("MY_THING");
  ASSERT_NE(mine, nullptr);
  EXPECT_EQ(mine->fields[0].name, "value");
  EXPECT_EQ(mine->fields[1].name, "flag");  // char[8] and uint8 keep definition order
  EXPECT_EQ(mine->fields[2].name, "label");
  EXPECT_EQ(mine->fields[3].name, "extra");
  EXPECT_TRUE(mine->fields[3].extension);
  EXPECT_EQ(mine->min_length, 17);
  EXPECT_EQ(mine->max_length, 19);
}

TEST(Dialect, ErrorsNameTheFileAndTheProblem) {
  const auto dir = test::temp_dir();
  MessageSet set = MessageSet::compiled();
  auto missing = load_dialect(dir + "/nope.xml", set);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("nope.xml"), std::string::npos);
  write(dir + "/bad.xml", "<mavlink><messages><message");
  auto bad = load_dialect(dir + "/bad.xml", set);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("not valid XML"), std::string::npos);
  write(dir + "/type.xml", R"(<mavlink><messages><message id="1" name="X"><field type="float128" name="f">f</field></message></messages></mavlink>)");
  auto type = load_dialect(dir + "/type.xml", set);
  ASSERT_FALSE(type.ok());
  EXPECT_NE(type.error().message.find("float128"), std::string::npos);
  EXPECT_EQ(set.size(), MessageSet::compiled().size());  // a failed load leaves the set as it was
}

TEST(Tlog, WritesAndReadsBackWithTimestamps) {
  const auto path = test::temp_dir() + "/t.tlog";
  FrameEncoder enc(1, 1);
  {
    auto w = TlogWriter::open(path);
    ASSERT_TRUE(w.ok());
    for (int i = 0; i < 10; ++i) {
      FrameBuffer buf;
      msg::Attitude a;
      a.time_boot_ms = static_cast<uint32_t>(i);
      a.roll = 0.1f * static_cast<float>(i);
      const std::size_t n = enc.encode(a, buf);
      ASSERT_TRUE(w->write(1700000000000000ULL + static_cast<uint64_t>(i) * 10000, {buf.data(), n}));
    }
    ASSERT_TRUE(w->flush());
  }
  // The timestamp is big-endian at the start of each record.
  std::ifstream raw(path, std::ios::binary);
  uint8_t first[9];
  raw.read(reinterpret_cast<char*>(first), 9);
  EXPECT_EQ(first[0], 0x00);
  EXPECT_EQ(first[8], kStxV2);

  auto r = TlogReader::open(path);
  ASSERT_TRUE(r.ok());
  TlogRecord rec;
  auto set = MessageSet::compiled();
  FrameParser parser(set);
  int i = 0;
  while (r->next(rec)) {
    EXPECT_EQ(rec.time_unix_us, 1700000000000000ULL + static_cast<uint64_t>(i) * 10000);
    parser.parse_datagram(rec.frame, [&](const Frame& f) { EXPECT_EQ(f.as<msg::Attitude>().time_boot_ms, static_cast<uint32_t>(i)); });
    ++i;
  }
  EXPECT_EQ(i, 10);
  EXPECT_EQ(parser.stats().frames, 10u);
}

TEST(Tlog, CorruptBytesAreSkippedAndReadingGoesOn) {
  const auto path = test::temp_dir() + "/c.tlog";
  FrameEncoder enc(1, 1);
  {
    auto w = TlogWriter::open(path);
    FrameBuffer buf;
    std::size_t n = enc.encode(msg::Heartbeat{}, buf);
    w->write(1, {buf.data(), n});
    const uint8_t junk[5] = {1, 2, 3, 4, 5};
    w->write(2, junk);  // a record whose "frame" is not one
    n = enc.encode(msg::Heartbeat{}, buf);
    w->write(3, {buf.data(), n});
  }
  auto r = TlogReader::open(path);
  TlogRecord rec;
  int records = 0;
  while (r->next(rec)) ++records;
  EXPECT_EQ(records, 2);
  EXPECT_GT(r->stats().skipped_bytes, 0u);
  EXPECT_FALSE(TlogReader::open("/nonexistent/x.tlog").ok());
}

TEST(SequenceTracker, CountsLossReorderingAndWrap) {
  SequenceTracker t;
  for (int s : {250, 251, 252, 255, 0, 1, 1, 5}) t.observe(static_cast<uint8_t>(s));
  EXPECT_EQ(t.stats().received, 8u);
  EXPECT_EQ(t.stats().lost, 2u + 3u);  // 253, 254 and 2, 3, 4
  EXPECT_EQ(t.stats().out_of_order, 1u);
}

}  // namespace
}  // namespace hitl::mavlink
