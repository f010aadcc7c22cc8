#include <gtest/gtest.h>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/inspect/expectations.h"
#include "engine/telemetry/interval_meter.h"
#include "engine/telemetry/traffic_json.h"
#include "engine/telemetry/traffic_stats.h"

namespace hitl {
namespace {

TEST(IntervalMeter, MeanStdMaxAndPercentilesOfKnownGaps) {
  telemetry::IntervalMeter m;
  int64_t t = 0;
  m.arrival(t);
  for (int i = 0; i < 1000; ++i) {
    t += (i % 5 < 3) ? 3'900'000 : 4'100'000;  // 600 gaps of 3900 us, 400 of 4100 us
    m.arrival(t);
  }
  t += 20'000'000;  // one late arrival
  m.arrival(t);
  const auto s = m.summary();
  EXPECT_EQ(s.count, 1001u);
  EXPECT_NEAR(s.mean_us, (600 * 3900.0 + 400 * 4100.0 + 20000.0) / 1001.0, 1e-6);
  EXPECT_NEAR(s.min_us, 3900.0, 1e-9);
  EXPECT_NEAR(s.max_us, 20000.0, 1e-9);
  EXPECT_NEAR(s.p50_us, 3900.0, 3900.0 * 0.005);
  EXPECT_NEAR(s.p99_us, 4100.0, 4100.0 * 0.005);
  EXPECT_GT(s.std_us, 100.0);
}

TEST(IntervalMeter, HugeGapsAndExtremeClocksNeitherOverflowNorCrash) {
  // Issue 19: two tlog records 6e14 us apart overflowed gap_ns * 16 and wrote out of bounds.
  telemetry::IntervalMeter m;
  m.arrival(0);
  m.arrival(600'000'000'000'000'000);  // 6e14 us later
  m.arrival(INT64_MAX);
  m.arrival(INT64_MIN);  // back in time: not a gap
  const auto s = m.summary();
  EXPECT_EQ(s.count, 2u);
  EXPECT_NEAR(s.min_us, 6e14, 1e3);
  EXPECT_NEAR(s.max_us, static_cast<double>(INT64_MAX) / 1000.0 - 6e14, 1e6);
  EXPECT_GE(s.p99_us, s.min_us);
  EXPECT_LE(s.p99_us, s.max_us);

  telemetry::IntervalMeter from_the_bottom;
  from_the_bottom.arrival(INT64_MIN);
  from_the_bottom.arrival(INT64_MAX);  // the widest gap two int64 times can have
  EXPECT_NEAR(from_the_bottom.summary().max_us, 1.8446744e16, 1e10);
}

TEST(IntervalMeter, HistogramHoldsOnlyTheBucketsItUses) {
  telemetry::IntervalMeter one;
  one.arrival(0);
  EXPECT_EQ(one.histogram_bytes(), 0u);  // a message seen once costs no histogram
  telemetry::IntervalMeter steady;
  for (int64_t i = 0; i < 2000; ++i) steady.arrival(i * 4'000'000 + (i % 7) * 50'000);
  EXPECT_LT(steady.histogram_bytes(), 2048u);
  EXPECT_NEAR(steady.summary().p50_us, 4000.0, 400.0);
}

TEST(TrafficStats, RatesBytesAndSourceLoss) {
  const auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::FrameEncoder enc(1, 1);
  telemetry::TrafficStats stats(0);
  mavlink::FrameBuffer buf;
  for (int i = 0; i < 251; ++i) {  // 250 Hz for one second, with one frame lost in the middle
    const std::size_t n = enc.encode(mavlink::msg::Odometry{}, buf);
    if (i == 100) continue;
    parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { stats.on_frame(f, "127.0.0.1:1", int64_t{i} * 4'000'000); });
  }
  const auto s = stats.summary(1'000'000'000, parser.stats());
  ASSERT_EQ(s.messages.size(), 1u);
  EXPECT_EQ(s.messages[0].name, "ODOMETRY");
  EXPECT_EQ(s.messages[0].count, 250u);
  EXPECT_NEAR(s.messages[0].rate_hz, 249.0, 0.01);  // 249 gaps in 1 s (one frame missing)
  ASSERT_EQ(s.sources.size(), 1u);
  EXPECT_EQ(s.sources[0].seq.lost, 1u);
  const auto j = telemetry::to_json(s);
  EXPECT_EQ(j["messages"]["ODOMETRY"]["id"], 331);
  EXPECT_TRUE(j["messages"]["ODOMETRY"]["gap_us"].contains("std"));
  EXPECT_EQ(j["sources"][0]["lost"], 1);
  // A stream that stopped: its rate falls as time goes on.
  const auto later = stats.summary(3'000'000'000, parser.stats());
  EXPECT_LT(later.messages[0].rate_hz, 100.0);
}

TEST(TrafficStats, TablesAreBoundedAndSayOnceWhenFull) {
  // Issue 19: every distinct id cost ~44 KB and the tables grew without end.
  telemetry::TrafficStats stats(0);
  mavlink::Frame f;
  int id_bounds = 0, source_bounds = 0;
  for (uint32_t i = 0; i < 5000; ++i) {
    f.msgid = 100000 + i;
    f.sysid = static_cast<uint8_t>(i);
    f.compid = static_cast<uint8_t>(i >> 8);
    switch (stats.on_frame(f, "127.0.0.1:1", int64_t{i} * 1000)) {
      case telemetry::TrafficStats::Bound::MessageIds: ++id_bounds; break;
      case telemetry::TrafficStats::Bound::Sources: ++source_bounds; break;
      case telemetry::TrafficStats::Bound::None: break;
    }
  }
  const auto s = stats.summary(5'000'000, {});
  EXPECT_EQ(s.frames, 5000u);
  EXPECT_EQ(s.messages.size(), telemetry::kMaxMessageIds);
  EXPECT_EQ(s.untracked_id_frames, 5000u - telemetry::kMaxMessageIds);
  EXPECT_EQ(s.sources.size(), telemetry::kMaxSources);
  EXPECT_EQ(s.untracked_source_frames, 5000u - telemetry::kMaxSources);
  EXPECT_EQ(id_bounds, 1);  // one message per bound
  EXPECT_EQ(source_bounds, 1);
  EXPECT_EQ(telemetry::to_json(s)["untracked_id_frames"], 5000u - telemetry::kMaxMessageIds);
}

TEST(Expectations, ParseAndJudge) {
  const auto set = mavlink::MessageSet::compiled();
  auto e = inspect::parse_expectations("odometry=250, HIL_SENSOR=250", set);
  ASSERT_TRUE(e.ok()) << e.error().message;
  ASSERT_EQ(e->size(), 2u);
  EXPECT_EQ((*e)[0].name, "ODOMETRY");
  EXPECT_FALSE(inspect::parse_expectations("NOPE=1", set).ok());
  EXPECT_FALSE(inspect::parse_expectations("ODOMETRY", set).ok());
  EXPECT_FALSE(inspect::parse_expectations("ODOMETRY=-3", set).ok());
  EXPECT_FALSE(inspect::parse_expectations("ODOMETRY=fast", set).ok());

  telemetry::TrafficSummary s;
  telemetry::MessageSummary odo;
  odo.id = 331;
  odo.name = "ODOMETRY";
  odo.count = 1000;
  odo.rate_hz = 240.0;
  s.messages.push_back(odo);
  auto r = inspect::check_expectations(s, *e, 5.0);
  EXPECT_TRUE(r[0].ok);  // 240 is within 237.5..262.5
  EXPECT_FALSE(r[1].ok);  // no HIL_SENSOR at all
  EXPECT_NE(r[1].verdict.find("none received"), std::string::npos);
  auto strict = inspect::check_expectations(s, *e, 2.0);
  EXPECT_FALSE(strict[0].ok);
  EXPECT_NE(strict[0].verdict.find("too slow"), std::string::npos);
}

}  // namespace
}  // namespace hitl
