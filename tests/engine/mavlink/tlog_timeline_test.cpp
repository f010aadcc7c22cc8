// A tlog's timestamps checked as they are read (issue 34): joins start segments, a lone bad stamp
// is set aside, a pause stays in its segment, and a log's first record needs no less confirming.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/message_set.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/tlog_timeline.h"
#include "tests/support/process.h"

namespace hitl::mavlink {
namespace {

/// Writes one HEARTBEAT record at each stamp and reads the file back through the timeline: the
/// stamps kept, a '|' before each that starts a segment.
struct Read {
  std::vector<std::string> kept;
  TimelineStats stats;
};

Read through_timeline(const std::vector<uint64_t>& stamps_us) {
  const auto path = test::temp_dir() + "/t.tlog";
  {
    auto w = TlogWriter::open(path);
    FrameEncoder enc(1, 1);
    FrameBuffer buf;
    for (uint64_t t : stamps_us) {
      const std::size_t n = enc.encode(gcs_heartbeat(), buf);
      EXPECT_TRUE(w->write(t, {buf.data(), n}));
    }
    EXPECT_TRUE(w->flush());
  }
  auto r = TlogReader::open(path);
  EXPECT_TRUE(r.ok());
  TlogTimeline timeline(std::move(r.value()));
  Read out;
  TimedRecord rec;
  while (timeline.next(rec)) out.kept.push_back((rec.new_segment ? "|" : "") + std::to_string(rec.record.time_unix_us));
  out.stats = timeline.timeline();
  return out;
}

constexpr uint64_t T = 1'700'000'000'000'000;  // 2023, in us
constexpr uint64_t ms = 1000, s = 1'000'000;

TEST(TlogTimeline, AJoinBackStartsASegment) {
  // (A pause of 2 s, three records, then the join: a jump is decided by the two records after it.)
  const auto r = through_timeline({T, T + 4 * ms, T + 8 * ms, T + 2 * s, T + 2 * s + 4 * ms, T + 2 * s + 8 * ms, T, T + 4 * ms, T + 8 * ms});
  EXPECT_EQ(r.kept, (std::vector<std::string>{std::to_string(T), std::to_string(T + 4 * ms), std::to_string(T + 8 * ms),
                                               std::to_string(T + 2 * s), std::to_string(T + 2 * s + 4 * ms),
                                               std::to_string(T + 2 * s + 8 * ms), "|" + std::to_string(T),
                                               std::to_string(T + 4 * ms), std::to_string(T + 8 * ms)}));
  EXPECT_EQ(r.stats.segments, 2u);
  EXPECT_EQ(r.stats.set_aside_records, 0u);
}

TEST(TlogTimeline, ALoneBadStampIsSetAsideWhereverItJumps) {
  for (uint64_t bad : {T + 7'000'000 * s, T - 30 * s, T + 30 * s, uint64_t{0}, ~uint64_t{0}}) {
    const auto r = through_timeline({T, T + 4 * ms, bad, T + 8 * ms, T + 12 * ms});
    EXPECT_EQ(r.kept.size(), 4u) << bad;
    EXPECT_EQ(r.stats.segments, 1u) << bad;
    EXPECT_EQ(r.stats.set_aside_records, 1u) << bad;
  }
  // Two bad ones in a row, then the log goes on; and a bad first and a bad last record.
  const auto two = through_timeline({T, T + 4 * ms, T + 900 * s, 5, T + 8 * ms});
  EXPECT_EQ(two.kept.size(), 3u);
  EXPECT_EQ(two.stats.set_aside_records, 2u);
  const auto ends = through_timeline({42, T, T + 4 * ms, T + 8 * ms, T + 9'999 * s});
  EXPECT_EQ(ends.kept, (std::vector<std::string>{std::to_string(T), std::to_string(T + 4 * ms), std::to_string(T + 8 * ms)}));
  EXPECT_EQ(ends.stats.set_aside_records, 2u);
  EXPECT_EQ(ends.stats.segments, 1u);
}

TEST(TlogTimeline, APauseUpToAMinuteStaysLongerStartsASegment) {
  const auto pause = through_timeline({T, T + 1 * s, T + 40 * s, T + 41 * s});
  EXPECT_EQ(pause.stats.segments, 1u);
  EXPECT_EQ(pause.kept.size(), 4u);
  const auto hours = through_timeline({T, T + 1 * s, T + 7200 * s, T + 7201 * s});
  EXPECT_EQ(hours.stats.segments, 2u);
  EXPECT_EQ(hours.kept.back(), std::to_string(T + 7201 * s));
  EXPECT_EQ(hours.kept[2], "|" + std::to_string(T + 7200 * s));
  // A slow stream (one record every 2 s) is a run of pauses, each confirmed by the next.
  const auto slow = through_timeline({T, T + 2 * s, T + 4 * s, T + 6 * s, T + 8 * s});
  EXPECT_EQ(slow.kept.size(), 5u);
  EXPECT_EQ(slow.stats.segments, 1u);
  EXPECT_EQ(slow.stats.set_aside_records, 0u);
}

TEST(TlogTimeline, AClockStepBackWithinASecondStays) {
  const auto r = through_timeline({T, T + 500 * ms, T + 100 * ms, T + 600 * ms});
  EXPECT_EQ(r.kept.size(), 4u);
  EXPECT_EQ(r.stats.segments, 1u);
  EXPECT_EQ(r.stats.set_aside_records, 0u);
}

TEST(TlogTimeline, BadStampsAheadDoNotRatchetTheLogsTimeAndABackJumpNeedsARecordBackToo) {
  // Bad stamps a little ahead: the first (0.9 s) is within 1 s and kept; the second is 1.7 s
  // ahead of the log's time, set aside; the records after them run on in one segment (measured
  // from the largest stamp so far, 1.7 s would have been kept and the rest made a jump back).
  const auto ratchet = through_timeline({T, T + 4 * ms, T + 900 * ms, T + 8 * ms, T + 1700 * ms, T + 12 * ms, T + 16 * ms});
  EXPECT_EQ(ratchet.stats.segments, 1u);
  EXPECT_EQ(ratchet.stats.set_aside_records, 1u);
  EXPECT_EQ(ratchet.kept.size(), 6u);
  // A bad stamp 8 s back, then the log runs on after a 1.5 s gap: the bad one is set aside, not a
  // segment confirmed by a record within a minute after it.
  const auto gap = through_timeline({T, T + 10 * s, T + 2 * s, T + 11500 * ms, T + 11504 * ms});
  EXPECT_EQ(gap.stats.segments, 1u);
  EXPECT_EQ(gap.stats.set_aside_records, 1u);
  EXPECT_EQ(gap.kept.back(), std::to_string(T + 11504 * ms));
}

TEST(TlogTimeline, TwoBadStampsOneAfterTheOtherAreSetAsideNotASegment) {
  // As a log with 1 % of its bytes flipped had them among the frames that still check: 7.5 s and
  // 3.7 s back, then the log runs on. One record back with the first confirmed it before.
  const auto r = through_timeline({T, T + 4 * ms, T - 7536 * ms, T - 3736 * ms, T + 8 * ms, T + 12 * ms});
  EXPECT_EQ(r.stats.segments, 1u);
  EXPECT_EQ(r.stats.set_aside_records, 2u);
  EXPECT_EQ(r.kept, (std::vector<std::string>{std::to_string(T), std::to_string(T + 4 * ms), std::to_string(T + 8 * ms),
                                               std::to_string(T + 12 * ms)}));
  // A bad stamp back, then a join back further (not running on from it): the bad one set aside, the
  // log goes on from the join once two records run on from it.
  const auto join = through_timeline({T, T + 4 * ms, T - 30 * s, T - 95 * s, T - 95 * s + 4 * ms, T - 95 * s + 8 * ms});
  EXPECT_EQ(join.stats.segments, 2u);
  EXPECT_EQ(join.stats.set_aside_records, 1u);
  EXPECT_EQ(join.kept[2], "|" + std::to_string(T - 95 * s));
  // The same ahead (1.8 s and 5.6 s): one record running on from the first confirmed it as a pause,
  // and the log's return made a second segment.
  const auto ahead = through_timeline({T, T + 4 * ms, T + 1772 * ms, T + 5575 * ms, T + 8 * ms, T + 12 * ms});
  EXPECT_EQ(ahead.stats.segments, 1u);
  EXPECT_EQ(ahead.stats.set_aside_records, 2u);
  EXPECT_EQ(ahead.kept.size(), 4u);
  // A join back as the log's last two records: kept.
  const auto last_two = through_timeline({T, T + 4 * ms, T - 30 * s, T - 30 * s + 4 * ms});
  EXPECT_EQ(last_two.stats.segments, 2u);
  EXPECT_EQ(last_two.kept.size(), 4u);
}

TEST(TlogTimeline, AOneRecordLogIsKept) {
  const auto r = through_timeline({T});
  EXPECT_EQ(r.kept.size(), 1u);
  EXPECT_EQ(r.stats.segments, 1u);
  EXPECT_EQ(through_timeline({}).stats.segments, 0u);
}

TEST(TlogTimeline, GivenTheMessagesARecordWhoseFrameDoesNotCheckNeitherMovesTimeNorDecides) {
  // Good HEARTBEATs, and between them "records" found in garbage: a frame whose checksum fails,
  // each under a stamp of whatever bytes preceded it (here ten years on, and a nearby pair that
  // would otherwise confirm each other as a segment).
  const auto path = test::temp_dir() + "/u.tlog";
  {
    auto w = TlogWriter::open(path);
    FrameEncoder enc(1, 1);
    FrameBuffer buf;
    auto good = [&](uint64_t t) {
      const std::size_t n = enc.encode(gcs_heartbeat(), buf);
      EXPECT_TRUE(w->write(t, {buf.data(), n}));
    };
    auto broken = [&](uint64_t t) {
      std::size_t n = enc.encode(gcs_heartbeat(), buf);
      buf[n - 1] ^= 0xFF;  // the checksum
      EXPECT_TRUE(w->write(t, {buf.data(), n}));
    };
    good(T);
    good(T + 4 * ms);
    broken(T + 315'000'000 * s);
    broken(T + 315'000'000 * s + 1 * ms);
    good(T + 8 * ms);
    good(T + 12 * ms);
    EXPECT_TRUE(w->flush());
  }
  const auto set = MessageSet::compiled();
  auto r = TlogReader::open(path);
  ASSERT_TRUE(r.ok());
  TlogTimeline timeline(std::move(r.value()), &set);
  TimedRecord rec;
  std::vector<bool> unchecked;
  while (timeline.next(rec)) {
    EXPECT_FALSE(rec.new_segment);
    unchecked.push_back(rec.unchecked);
  }
  EXPECT_EQ(unchecked, (std::vector<bool>{false, false, true, true, false, false}));
  EXPECT_EQ(timeline.timeline().segments, 1u);
  EXPECT_EQ(timeline.timeline().set_aside_records, 0u);
}

}  // namespace
}  // namespace hitl::mavlink
