// What arrived on a MAVLink link, per message and per source: counts, rates,
// inter-arrival gaps, bytes, sequence loss, and the parser's error counters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "base/mavlink/frame.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/sequence_tracker.h"
#include "engine/telemetry/interval_meter.h"

namespace hitl::telemetry {

struct MessageSummary {
  uint32_t id = 0;
  std::string name;  ///< "#1234" for ids the message set does not know
  uint64_t count = 0;
  double rate_hz = 0;         ///< (count - 1) / (now - first arrival): falls when a stream stops
  double recent_rate_hz = 0;  ///< over the last window (see TrafficStats::roll)
  GapSummary gap;
  uint64_t bytes = 0;
  double bytes_per_s = 0;
};

struct SourceSummary {
  std::string address;  ///< where datagrams came from ("127.0.0.1:14561"), or "tlog"
  uint8_t sysid = 0;
  uint8_t compid = 0;
  mavlink::SequenceStats seq;
};

/// Bounds on the tables that grow with outside input (distinct ids, distinct senders).
inline constexpr std::size_t kMaxMessageIds = 1024;  ///< more than any dialect defines
inline constexpr std::size_t kMaxSources = 256;      ///< (address, sysid, compid) triples

struct TrafficSummary {
  double duration_s = 0;
  uint64_t frames = 0;
  uint64_t datagrams = 0;
  uint64_t untracked_id_frames = 0;      ///< frames of ids past kMaxMessageIds: counted, not in `messages`
  uint64_t untracked_source_frames = 0;  ///< frames of senders past kMaxSources: counted, not in `sources`
  mavlink::ParserStats parser;
  uint64_t segments = 1;            ///< stretches measured on their own (a tlog's, tlog_timeline.h; live: 1)
  uint64_t set_aside_records = 0;   ///< a tlog's records whose stamp jumped, not measured
  std::vector<MessageSummary> messages;  ///< by id
  std::vector<SourceSummary> sources;

  const MessageSummary* message(std::string_view name) const;
};

class TrafficStats {
 public:
  /// Starts the measurement at `start_ns` (any clock, as long as arrivals use the same one).
  explicit TrafficStats(int64_t start_ns = 0) : start_ns_(start_ns), window_start_ns_(start_ns) {}
  void restart(int64_t start_ns);

  void on_datagram() { ++datagrams_; }
  enum class Bound { None, MessageIds, Sources };
  /// Counts a frame; returns which table bound this frame hit for the first time (None otherwise).
  Bound on_frame(const mavlink::Frame& frame, const std::string& source, int64_t t_ns);
  /// Ends the measured stretch at `end_ns` and starts another at `start_ns` (a tlog's next segment):
  /// rates, durations and sequences count within segments, never across the join.
  void new_segment(int64_t end_ns, int64_t start_ns);
  /// Closes the current rate window at `now_ns` (recent_rate_hz covers it) and opens the next.
  void roll(int64_t now_ns);

  /// A snapshot at `now_ns` (the current segment's end so far); `parser` is the parser's own counters, copied in.
  TrafficSummary summary(int64_t now_ns, const mavlink::ParserStats& parser) const;

 private:
  struct Meter {
    std::string name;
    uint64_t count = 0;
    uint64_t bytes = 0;
    uint64_t window_count = 0;
    double recent_rate_hz = 0;
    IntervalMeter gaps;
  };
  int64_t start_ns_;  ///< the current segment's
  int64_t window_start_ns_;
  double closed_duration_ns_ = 0;  ///< the segments before the current one
  uint64_t segments_ = 1;
  uint64_t frames_ = 0;
  uint64_t datagrams_ = 0;
  uint64_t untracked_id_frames_ = 0;
  uint64_t untracked_source_frames_ = 0;
  std::map<uint32_t, Meter> meters_;
  std::map<std::tuple<std::string, uint8_t, uint8_t>, mavlink::SequenceTracker> sources_;
};

}  // namespace hitl::telemetry
