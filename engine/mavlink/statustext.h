// STATUSTEXT's chunks, both ways: a text longer than the field's 50 characters goes out as chunks that share
// an `id`, numbered by `chunk_seq` from 0; the chunk holding a NUL is the last (MAVLink common.xml).
// PX4 v1.16 (streams/STATUSTEXT.hpp) numbers every text, single-chunk ones too, starts at id 0, and
// sends no closing chunk when the text fills its last chunk exactly; so a full chunk is held until
// the source's next text or a short wait, and id 0 is treated like any other id.
// hitl's own long texts go out the same way (StatusTextChunker).
// Every place hitl shows a STATUSTEXT (arm/fly, dashboards, inspect, doctor, report, JSON) reads it
// through this, so "Arming denied: ..." arrives whole, never as its last 50 characters.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/mavlink/frame.h"
#include "base/mavlink/messages.h"

namespace hitl::mavlink {

/// One logical status text, its chunks joined.
struct StatusText {
  uint8_t sysid = 0;
  uint8_t compid = 0;
  uint8_t severity = 0;  ///< MAV_SEVERITY of its first chunk
  std::string text;      ///< joined; "[ missing ... ]" where a chunk never came (as PX4's own handler writes it)
  int chunks = 0;        ///< chunks received
  bool incomplete = false;  ///< a chunk is missing, or the last never came
  double first_chunk_s = 0;  ///< when its first chunk arrived (the caller's clock)
};

class StatusTextAssembler {
 public:
  /// A text whose closing chunk has not come is given out as it is this long after its last chunk.
  static constexpr double kChunkWait_s = 0.5;
  /// Bounds, whatever a sender does: chunks per text (PX4's longest text, 127 characters, takes 3)
  /// and texts being assembled at once (the oldest is given out first when more start).
  static constexpr int kMaxChunks = 8;
  static constexpr std::size_t kMaxPending = 16;

  /// The texts this chunk completes: none (more chunks to come), one, or more (a chunk of a new text
  /// from the same source closes the one before it).
  std::vector<StatusText> on_statustext(uint8_t sysid, uint8_t compid, const msg::Statustext& chunk, double now_s);
  /// The same for a frame; frames that are not STATUSTEXT give nothing.
  std::vector<StatusText> on_frame(const Frame& frame, double now_s);
  /// Texts whose chunks stopped kChunkWait_s ago, given out as they are.
  std::vector<StatusText> expire(double now_s);
  /// Everything still held (at the end of a log or a command).
  std::vector<StatusText> flush();

 private:
  struct Pending {
    StatusText text;
    uint16_t id = 0;
    int last_chunk_seq = 0;
    double last_chunk_s = 0;
  };
  std::vector<Pending> pending_;
};

/// Splits a text into STATUSTEXT chunks as PX4 does: 50 characters each, the last NUL-padded
/// (none when the text fills it exactly); a text of one chunk has id 0 (the only chunk), a longer
/// one the next id from 1 (0 is skipped when the counter wraps). Cut at kMaxChunks chunks.
class StatusTextChunker {
 public:
  std::vector<msg::Statustext> split(uint8_t severity, std::string_view text);

 private:
  uint16_t next_id_ = 1;
};

/// A status text made safe for a terminal: control characters (from the network) become spaces.
std::string printable_statustext(const std::string& text);

}  // namespace hitl::mavlink
