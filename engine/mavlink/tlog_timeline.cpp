#include "engine/mavlink/tlog_timeline.h"

#include <algorithm>

namespace hitl::mavlink {
namespace {

constexpr uint64_t kJump_us = static_cast<uint64_t>(TlogTimeline::kJump_s * 1e6);
constexpr uint64_t kMaxGap_us = static_cast<uint64_t>(TlogTimeline::kMaxGap_s * 1e6);

/// `t_us` within `before_us` before `from_us` and `after_us` after it (unsigned: no overflow).
bool near(uint64_t t_us, uint64_t from_us, uint64_t before_us, uint64_t after_us) {
  return t_us >= from_us ? t_us - from_us <= after_us : from_us - t_us <= before_us;
}

}  // namespace

bool TlogTimeline::checks(const TlogRecord& record) {
  if (!checker_) return true;
  bool valid = false;
  checker_->parse_datagram(record.frame, [&](const Frame& f) { valid = valid || f.desc != nullptr; });
  return valid;
}

void TlogTimeline::keep(TlogRecord record, bool new_segment) {
  if (!time_us_ || new_segment) {
    ++stats_.segments;
    new_segment = time_us_.has_value();
    time_us_ = record.time_unix_us;
  }
  // The last kept stamp, not the largest: one bad stamp a little ahead (kept, within kJump_s) must
  // not ratchet the log's time away from the records after it.
  time_us_ = record.time_unix_us;
  ready_.push_back({std::move(record), new_segment});
}

void TlogTimeline::keep_jumped() {
  // The log goes on from the jumped record: a new segment unless it was a pause forward.
  const uint64_t jumped_us = jumped_->time_unix_us;
  const bool pause = time_us_ && jumped_us > *time_us_ && jumped_us - *time_us_ <= kMaxGap_us;
  keep(std::move(*jumped_), !pause);
  jumped_.reset();
  if (confirm_) keep(std::move(*confirm_), false);
  confirm_.reset();
}

void TlogTimeline::judge_after_jump(TlogRecord r) {
  for (;;) {
    const uint64_t jumped_us = jumped_->time_unix_us;
    if (time_us_ && near(r.time_unix_us, *time_us_, kJump_us, kJump_us)) {
      // The log runs on from before the jump: the jump (and a record running on from it) were bad stamps.
      stats_.set_aside_records += confirm_ ? 2 : 1;
      jumped_.reset();
      confirm_.reset();
      keep(std::move(r), false);
      return;
    }
    const bool back = time_us_ && jumped_us < *time_us_;
    const TlogRecord& last = confirm_ ? *confirm_ : *jumped_;
    // Runs on from the jumped record (a jump back: only a record that is back too, not one running
    // on, after a gap, from the log's time).
    const bool runs_on = near(r.time_unix_us, last.time_unix_us, kJump_us, kMaxGap_us) &&
                         (!back || r.time_unix_us + kJump_us < *time_us_);
    if (runs_on && !confirm_ && time_us_) {  // (the log's first record: one record decides)
      // A jump needs two records running on from it: in a log with 1 % of its bytes flipped, two
      // bad stamps a few seconds apart, one after the other among the frames that still check,
      // are common enough (a join or a pause has hundreds of records after it).
      confirm_ = std::move(r);
      return;
    }
    if (runs_on) {
      keep_jumped();
      // This one is judged afresh from there: it runs on, or it jumps (a slow stream's next record).
      if (near(r.time_unix_us, *time_us_, kJump_us, kJump_us)) keep(std::move(r), false);
      else jumped_ = std::move(r);
      return;
    }
    ++stats_.set_aside_records;  // neither: the jumped one goes
    if (!confirm_) {
      jumped_ = std::move(r);  // this one (a jump too) waits in its place
      return;
    }
    jumped_ = std::move(*confirm_);  // the record after it takes its place; this one is judged against it
    confirm_.reset();
  }
}

bool TlogTimeline::next(TimedRecord& out) {
  TlogRecord r;
  while (ready_.empty()) {
    if (!reader_.next(r)) {
      if (!jumped_) return false;
      if (confirm_) {  // a jump and one record running on from it, the log's last two: kept
        keep_jumped();
        break;
      }
      // The last record jumped: kept when nothing contradicts it (the log's only record, or a
      // pause ahead of at most kMaxGap_s, as a slow stream's last), else set aside.
      if (!time_us_ || near(jumped_->time_unix_us, *time_us_, 0, kMaxGap_us)) {
        keep(std::move(*jumped_), false);
        jumped_.reset();
        break;
      }
      ++stats_.set_aside_records;
      jumped_.reset();
      return false;
    }
    if (!checks(r)) {  // says nothing about the log's time
      ready_.push_back({std::move(r), false, true});
      continue;
    }
    if (!jumped_) {
      if (time_us_ && near(r.time_unix_us, *time_us_, kJump_us, kJump_us)) keep(std::move(r), false);
      else jumped_ = std::move(r);  // the first record too waits for a second to confirm it
      continue;
    }
    judge_after_jump(std::move(r));
  }
  out = std::move(ready_.front());
  ready_.pop_front();
  return true;
}

}  // namespace hitl::mavlink
