// libFuzzer target for what `hitl inspect --tlog` does with a log from another tool: the tlog
// reader, the frame parser, the traffic tables with their interval meters (issue 19: a 6e14 us
// gap overflowed there), the timeline's segments (issue 34: a joined or corrupted log measured
// across its jumps), the summary and its JSON. The input is the whole file.
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/tlog_timeline.h"
#include "engine/telemetry/traffic_json.h"
#include "engine/telemetry/traffic_stats.h"
#include "tests/fuzz/fuzz_check.h"

namespace {

using namespace hitl;

// One in-memory file, rewritten for each input, read back through its /proc path.
const std::string& log_path() {
  static const std::string path = [] {
    const int fd = memfd_create("hitl-tlog-fuzz", 0);
    return "/proc/self/fd/" + std::to_string(fd);
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  static const mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  const int fd = std::stoi(log_path().substr(14));
  FUZZ_CHECK(ftruncate(fd, 0) == 0);
  FUZZ_CHECK(pwrite(fd, bytes, size, 0) == static_cast<ssize_t>(size));

  auto opened = mavlink::TlogReader::open(log_path());
  FUZZ_CHECK(opened.ok());
  // As inspect reads it: through the timeline, a new segment at each jump it confirms.
  mavlink::TlogTimeline reader(std::move(opened.value()), &messages);
  mavlink::FrameParser parser(messages);
  telemetry::TrafficStats stats;
  mavlink::TimedRecord timed;
  const mavlink::TlogRecord& rec = timed.record;
  bool started = false;
  int64_t now_ns = 0;
  uint64_t records = 0, segments = 0;
  while (reader.next(timed)) {
    ++records;
    FUZZ_CHECK(!rec.frame.empty() && rec.frame.size() <= mavlink::kMaxFrameLen);
    if (timed.unchecked) {  // as inspect: counted by the parser, its stamp ignored
      FUZZ_CHECK(!timed.new_segment);
      stats.on_datagram();
      parser.parse_datagram(rec.frame, [&](const mavlink::Frame&) {});
      continue;
    }
    const int64_t t = rec.time_unix_us > static_cast<uint64_t>(INT64_MAX / 1000) ? INT64_MAX
                                                                                : static_cast<int64_t>(rec.time_unix_us) * 1000;
    FUZZ_CHECK(!(timed.new_segment && !started));
    if (!started) {
      stats.restart(t);
      now_ns = t;
      segments = 1;
    } else if (timed.new_segment) {
      stats.new_segment(now_ns, t);
      now_ns = t;
      ++segments;
    }
    started = true;
    now_ns = std::max(now_ns, t);
    stats.on_datagram();
    parser.parse_datagram(rec.frame, [&](const mavlink::Frame& f) {
      if (f.desc != nullptr) stats.on_frame(f, "tlog", t);
    });
    if (records % 64 == 0) stats.roll(now_ns);
  }
  FUZZ_CHECK(reader.stats().records == records + reader.timeline().set_aside_records);
  FUZZ_CHECK(reader.timeline().segments == segments);
  FUZZ_CHECK(reader.stats().skipped_bytes <= size);
  FUZZ_CHECK(reader.stats().truncated <= 1);
  const auto summary = stats.summary(now_ns, parser.stats());
  FUZZ_CHECK(summary.messages.size() <= telemetry::kMaxMessageIds);
  FUZZ_CHECK(summary.segments == std::max<uint64_t>(segments, 1));
  // Within a segment the log's time goes on by at most a pause (60 s) a record: never years.
  FUZZ_CHECK(summary.duration_s >= 0 && summary.duration_s <= static_cast<double>(records) * 61.0 + 1.0);
  for (const auto& m : summary.messages) FUZZ_CHECK(std::isfinite(m.rate_hz) && m.rate_hz >= 0 && std::isfinite(m.bytes_per_s));
  for (const auto& m : summary.messages) {
    FUZZ_CHECK(m.gap.min_us <= m.gap.p50_us && m.gap.p50_us <= m.gap.max_us);
    FUZZ_CHECK(m.gap.p99_us <= m.gap.max_us);
  }
  FUZZ_CHECK(!telemetry::to_json(summary).dump().empty());
  return 0;
}
