// A tlog's timestamps checked as they are read. A log's clock is outside input: logs joined with
// `cat` jump back at each join, a corrupted stamp jumps anywhere (year 2262), a ground station left
// running jumps forward by hours. Measuring across such a jump gives rates that are wrong by any
// factor; measuring within the stretches that run on gives the true ones.
//
// Rules: a record more than kJump_s before or after the log's time so far is a jump, and the next
// two records decide it. When the next runs on from the log's time, the jumped one is set aside (a
// corrupted stamp: counted, not measured). When the next two run on from the jumped one, each from
// the one before (within kMaxGap_s after it; after a jump back, only records that are back too), the
// log goes on from there: a jump back or a jump forward of more than kMaxGap_s
// starts a new segment, a shorter pause stays in the segment. The last record, when it jumped, is
// kept as a pause (ahead by at most kMaxGap_s) or when it is the log's only one, else set aside. Within kJump_s a record's time
// may go back a little (a clock step): it stays.
//
// Given the message set, only a record whose frame checks (a known message, its checksum right)
// counts: one that does not (a corrupted frame, or "a record" found inside garbage, whose stamp is
// whatever bytes preceded it) is released at once as unchecked, neither moving the log's time nor
// deciding a jump; its frame fails the parser where the caller counts it.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/mavlink/tlog.h"

namespace hitl::mavlink {

struct TimelineStats {
  uint64_t segments = 0;           ///< stretches of the log measured on their own (0: no record kept)
  uint64_t set_aside_records = 0;  ///< records whose stamp no neighbour confirmed: not measured
};

/// One record as the timeline releases it.
struct TimedRecord {
  TlogRecord record;
  bool new_segment = false;  ///< the first record of a segment after the first
  bool unchecked = false;    ///< its frame does not check: its stamp says nothing (use the log's time)
};

class TlogTimeline {
 public:
  static constexpr double kJump_s = 1.0;
  static constexpr double kMaxGap_s = 60.0;

  /// `messages` (kept by the caller): judge only records whose frame checks; none: every record.
  explicit TlogTimeline(TlogReader reader, const MessageSet* messages = nullptr)
      : reader_(std::move(reader)), messages_(messages) {
    if (messages_ != nullptr) checker_.emplace(*messages_);
  }
  /// The next record kept, in file order; false at the end of the log.
  bool next(TimedRecord& out);
  const TimelineStats& timeline() const { return stats_; }
  const TlogStats& stats() const { return reader_.stats(); }
  TlogReader& reader() { return reader_; }

 private:
  void keep(TlogRecord record, bool new_segment);
  /// Keeps the jumped record (a new segment unless a pause forward) and the one confirming it.
  void keep_jumped();
  /// `r` (its frame checks) after a jumped record: sets the jumped one aside or keeps it.
  void judge_after_jump(TlogRecord r);

  bool checks(const TlogRecord& record);

  TlogReader reader_;
  const MessageSet* messages_ = nullptr;
  std::optional<FrameParser> checker_;
  std::optional<uint64_t> time_us_;  ///< the log's time so far (the last kept stamp)
  std::optional<TlogRecord> jumped_;  ///< a record that jumped, waiting for the next to decide
  std::optional<TlogRecord> confirm_;  ///< after a jump, a record running on from it, waiting for a third
  std::deque<TimedRecord> ready_;
  TimelineStats stats_;
};

}  // namespace hitl::mavlink
