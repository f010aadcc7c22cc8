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

bool TlogTimeline::next(TimedRecord& out) {
  TlogRecord r;
  while (ready_.empty()) {
    if (!reader_.next(r)) {
      if (!jumped_) return false;
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
    const uint64_t jumped_us = jumped_->time_unix_us;
    if (time_us_ && near(r.time_unix_us, *time_us_, kJump_us, kJump_us)) {
      ++stats_.set_aside_records;  // the log runs on from before the jump: the jump was a bad stamp
      jumped_.reset();
      keep(std::move(r), false);
    } else if (near(r.time_unix_us, jumped_us, kJump_us, kMaxGap_us) &&
               (!time_us_ || jumped_us > *time_us_ || r.time_unix_us + kJump_us < *time_us_)) {
      // (A jump back is confirmed only by a record that is back too, not one running on, after
      // a gap, from the log's time.)
      // The log goes on from the jumped record: a new segment unless it was a pause forward.
      const bool pause = time_us_ && jumped_us > *time_us_ && jumped_us - *time_us_ <= kMaxGap_us;
      keep(std::move(*jumped_), !pause);
      jumped_.reset();
      keep(std::move(r), false);
    } else {
      ++stats_.set_aside_records;  // neither: the jumped one goes, this one (a jump too) waits in its place
      jumped_ = std::move(r);
    }
  }
  out = std::move(ready_.front());
  ready_.pop_front();
  return true;
}

}  // namespace hitl::mavlink
